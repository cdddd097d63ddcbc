#pragma once

// The flight plan tab: a QGroundControl mission loaded from a .plan file, its
// items in a table, and its upload to the aircraft in BLOCK 2 sections with
// the progress of each pass and the aircraft's acknowledgement.

#include "ui/plan/FlightPlanUpload.h"
#include "link/plan/MissionPlan.h"

#include <QWidget>

#include <optional>

class QLabel;
class QProgressBar;
class QPushButton;
class QTableWidget;

class FlightPlanWidget : public QWidget {
    Q_OBJECT

public:
    enum Column {
        SeqColumn,
        CommandColumn,
        FrameColumn,
        LatitudeColumn,
        LongitudeColumn,
        AltitudeColumn,
        Param1Column
    };
    static constexpr int kColumnCount = Param1Column + 4;

    // `upload` carries the plan to the link; it must outlive this widget.
    explicit FlightPlanWidget(FlightPlanUpload* upload, QWidget* parent = nullptr);

    // Shows the plan; on an error keeps the plan shown before and says why.
    bool loadPlan(const QString& path, QString* error = nullptr);
    const std::optional<MissionPlan>& plan() const { return m_plan; }
    QTableWidget* table() const { return m_table; }
    // "9 mission items, 322 bytes, 2 BLOCK 2 sections"; empty before a plan.
    QString summary() const;

    // Uploads go out only while a link that can send is running.
    void setLinkReady(bool ready);

public slots:
    void openPlan();  // asks for a file
    void uploadPlan();
    void cancelUpload();

signals:
    void message(const QString& text);  // for the status bar

private:
    void showPlan();
    void showProgress(const FlightPlanUpload::Progress& progress);
    void updateButtons();

    FlightPlanUpload* m_upload;
    std::optional<MissionPlan> m_plan;
    bool m_linkReady = false;
    QLabel* m_file;
    QLabel* m_summary;
    QTableWidget* m_table;
    QPushButton* m_open;
    QPushButton* m_send;
    QPushButton* m_cancel;
    QProgressBar* m_progress;
    QLabel* m_state;
};
