#pragma once

// The console at a glance, one page: the link's health in large figures
// (state, frames sent and received, bytes corrected, frames beyond correction
// and refused, age of the last good frame), every unit's commanded and
// reported values side by side in compact cards that flow into as many
// columns as the width allows, and the link's quality per minute over the
// last hour. The rows come from the item table, the values from CommandState
// and ReportedState; the reported column is ReportedLabel, so it highlights a
// lasting mismatch exactly as the panels do.
//
// In a replay the state reads "Replay" and the age gives way to the log's
// own time.

#include "codec/message/ItemTable.h"
#include "codec/message/Message.h"
#include "link/session/LinkStatistics.h"
#include "ui/overview/LinkQualityHistory.h"
#include "ui/panels/UnitRef.h"

#include <QTimer>
#include <QWidget>

#include <functional>
#include <optional>
#include <vector>

class CommandState;
class LinkQualityPlot;
class QBoxLayout;
class QGroupBox;
class QHBoxLayout;
class QLabel;
class ReportedLabel;
class ReportedState;

class OverviewPage : public QWidget {
    Q_OBJECT

public:
    // Microseconds since the epoch, UTC; tests pass a virtual clock.
    using Clock = std::function<qint64()>;

    // `command` and `reported` must outlive the page.
    OverviewPage(CommandState* command, ReportedState* reported, QWidget* parent = nullptr);

    void setClock(Clock clock);
    const LinkQualityHistory& history() const { return m_history; }

    // The figures shown, for tests and screenshots: "state", "sent",
    // "received", "corrected", "uncorrectable", "refused", "age".
    QString figure(const QString& name) const;
    // One unit's row: the commanded text, and the label with the reported one.
    QString commandedText(UnitRef ref, rcm::ItemId id, int field = -1) const;
    ReportedLabel* reportedLabel(UnitRef ref, rcm::ItemId id, int field = -1) const;
    int rowCount() const { return int(m_rows.size()); }
    int cardColumns() const { return m_columns; }
    // Below this width the plot goes under the figures rather than beside them.
    static constexpr int kSideBySideWidth = 900;
    static constexpr int kCardSpacing = 5;

public slots:
    void setStatistics(const LinkStatistics& statistics);
    // A replay: "Replay" instead of the link's state, the log's time instead of the age.
    void setReplay(bool replay);
    void setReplayTime(qint64 utcMicros);
    // Once a second from its own timer: the age, a sample for the plot.
    void tick();

protected:
    void resizeEvent(QResizeEvent* event) override;
    bool eventFilter(QObject* watched, QEvent* event) override;
    void changeEvent(QEvent* event) override;

private:
    struct Row {
        UnitRef ref;
        rcm::ItemId id;
        int field;
        QLabel* commanded;
        ReportedLabel* reported;
        // What `commanded` shows: every change of the command refreshes
        // every row, and most rows' values have not changed.
        std::optional<rcm::Value> shown;
        bool shownOnce = false;
    };
    QWidget* buildHealth();
    void rebuildUnits();
    void refreshCommanded();
    void reflow();
    // The height of each of `columns` columns with the cards placed in order,
    // each into the shortest; `placed` gets each card's column.
    std::vector<int> columnHeights(int columns, std::vector<std::size_t>* placed) const;
    void reflowFigures();
    void updateFigures();
    const Row* findRow(UnitRef ref, rcm::ItemId id, int field) const;

    CommandState* m_command;
    ReportedState* m_reported;
    Clock m_clock;
    LinkStatistics m_statistics;
    LinkQualityHistory m_history;
    bool m_replay = false;
    qint64 m_replayTime = 0;
    QString m_stateColour;  // the link state figure's colour, "#1b5e20"; empty: the page's own
    QTimer m_timer;

    std::vector<std::pair<QString, QLabel*>> m_figures;
    std::vector<QWidget*> m_figureBoxes;  // caption over value, re-gridded to the width
    class QGridLayout* m_healthGrid = nullptr;
    int m_figuresPerRow = 0;
    QWidget* m_unitArea;
    QHBoxLayout* m_unitColumns;
    std::vector<QGroupBox*> m_cards;
    std::vector<Row> m_rows;
    int m_columns = 0;
    int m_cardWidth = 1;  // every card's, from the font (rebuildUnits())
    QBoxLayout* m_top = nullptr;
    LinkQualityPlot* m_plot;
};
