#pragma once

// The frame log on screen: a filter bar (direction, status), the table of
// frames, and under it the selected frame decoded into the text format and
// as a hex dump. Only the selected frame is decoded in full.

#include "ui/table/TablePane.h"

class FrameLogFilterModel;
class FrameLogModel;
class QCheckBox;
class QComboBox;
class QLabel;
class QLayout;
class QPlainTextEdit;

class FrameLogView : public TablePane {
    Q_OBJECT

public:
    explicit FrameLogView(FrameLogModel* model, QWidget* parent = nullptr);

    // Keeps the newest frame in view as frames arrive (on by default).
    void setFollowing(bool on);
    bool isFollowing() const;
    // Scrolls to and selects the source row; nothing when it is filtered out.
    void showSourceRow(int sourceRow);
    // Scrolls the source row (or the next one shown) into view, selecting nothing.
    void scrollToSourceRow(int sourceRow);

    QString detailText() const;
    QString hexText() const;

private:
    // The row above the table: which frames to show, following, the count.
    QLayout* filterBar();
    // Fixed rows and columns, a steady scroll bar: a day's log stays cheap.
    void setUpTable();
    void applyFilter();
    void showSelected();
    void updateCount();

    FrameLogModel* m_model;
    FrameLogFilterModel* m_filter;
    QComboBox* m_direction;
    QComboBox* m_status;
    QCheckBox* m_follow;
    QLabel* m_count;
    QPlainTextEdit* m_detail;
    QPlainTextEdit* m_hex;
};
