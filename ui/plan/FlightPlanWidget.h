#pragma once

// The flight plan page: a plan loaded from a file of another program
// (QGroundControl, Mission Planner, KML), on a map that takes the page and
// in a table beside it, edited on the map, saved as a .plan, and its upload to the
// aircraft in BLOCK 2 sections with the progress of each pass, the time left
// at the rate the link really sends, and what the aircraft says it holds.
//
// Edits change the plan shown, never the plan being sent: an upload sends
// the bytes of the plan as it was when the operator pressed Upload, so the
// next frame's BLOCK 2 section is unaffected until the operator uploads.

#include "link/maptiles/MapTiles.h"
#include "link/plan/MissionPlan.h"
#include "ui/plan/FlightPlanUpload.h"

#include <QWidget>

#include <functional>
#include <optional>

class NoteLabel;
class PlanMapView;
class QLabel;
class QSplitter;
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
    // A plan whose one pass takes longer than this is uploaded only after the
    // operator confirms, having been told how long it takes.
    static constexpr double kLongUploadSeconds = 10 * 60;
    // Seconds a section before the link has sent two: the frame cadence.
    static constexpr double kNominalSecondsPerSection = 1.0;
    // The altitude given to a waypoint added on the map when there is no
    // positioned item before it, metres above home.
    static constexpr double kNewWaypointAltitude = 100;
    // Altitudes the table takes, metres: below the Dead Sea's shore, above
    // any ceiling a fixed-wing aircraft of this kind flies.
    static constexpr double kLowestAltitude = -500;
    static constexpr double kHighestAltitude = 20000;
    // Rows the table measures for its column widths.
    static constexpr int kRowsMeasured = 100;

    // `upload` carries the plan to the link; it must outlive this widget.
    explicit FlightPlanWidget(FlightPlanUpload* upload, QWidget* parent = nullptr);
    ~FlightPlanWidget() override;

    // Shows the plan; on an error keeps the plan shown before and says why.
    bool loadPlan(const QString& path, QString* error = nullptr);
    bool savePlan(const QString& path, QString* error = nullptr);
    const std::optional<MissionPlan>& plan() const { return m_plan; }
    QTableWidget* table() const { return m_table; }
    PlanMapView* map() const { return m_map; }
    MapTiles* tiles() const { return m_tiles; }
    // "9 mission items, 322 bytes, 2 BLOCK 2 sections, 2 s a pass"; empty before a plan.
    QString summary() const;
    // The text beside the progress bar: state, pass, time left.
    QString uploadState() const;
    // True when the plan shown differs from the one last uploaded.
    bool isEdited() const { return m_edited; }

    // "Edit plan": while off (the default, and after every plan opened) the
    // map and the table only select; nothing changes the plan.
    void setEditing(bool on);
    bool isEditing() const;

    // Uploads go out only while a link that can send is running.
    void setLinkReady(bool ready);
    void setTileSettings(const TileSettings& settings);

    // Asks the operator to confirm `text` with a button named `action`; the
    // default shows a Confirmation (Cancel is the default). Tests replace it.
    using Confirm = std::function<bool(const QString& text, const QString& action)>;
    void setConfirm(Confirm confirm) { m_confirm = std::move(confirm); }

    // The edits the map asks for, also for tests and keyboard use.
    void moveItem(int index, const GeoPoint& to);
    void addWaypoint(const GeoPoint& at);
    void deleteItem(int index);
    void setItemAltitude(int index, double metres);

public slots:
    void openPlan();  // asks for a file
    void savePlanAs();
    void chooseTiles();
    void uploadPlan();
    void cancelUpload();

signals:
    void message(const QString& text);  // for the status bar and the event log
    void planOpened(const QString& path);  // a plan file was read and is shown: bring it forward
    void problem(const QString& text);  // an error the operator must see: the event log and the banner

private:
    // The constructor's parts: the table's columns and behaviour, the
    // layout (file and summary on top, the table beside the map, the upload
    // at the bottom), and the connections of buttons, table, map and tiles.
    void setUpTable();
    void layOut();
    void connectParts();
    void showPlan();
    void showRow(int row);
    void showSummary();  // the summary line and the bar's sections
    void planEdited();
    void showProgress(const FlightPlanUpload::Progress& progress);
    void showAcknowledgement(const FlightPlanUpload::Progress& progress);
    void updateButtons();
    void selectRow(int row);
    void cellEdited(int row, int column);
    int sectionsFor(qsizetype bytes) const;
    void setProgressRange(int sections);

    FlightPlanUpload* m_upload;
    MapTiles* m_tiles;
    std::optional<MissionPlan> m_plan;
    std::optional<MissionPlan> m_sentPlan;  // as it was when the last upload started
    bool m_edited = false;
    bool m_linkReady = false;
    bool m_filling = false;  // the table is being filled, not edited
    Confirm m_confirm;
    QLabel* m_file;
    NoteLabel* m_summary;
    NoteLabel* m_edits;
    QLabel* m_mapSource;
    QTableWidget* m_table;
    PlanMapView* m_map;
    QPushButton* m_open;
    QPushButton* m_save;
    QPushButton* m_editOnMap;
    QPushButton* m_tileButton;
    QPushButton* m_send;
    QPushButton* m_cancel;
    QProgressBar* m_progress;
    NoteLabel* m_state;
    QSplitter* m_split = nullptr;
};
