#pragma once

// The link pane's part for control between stations (docs/protocol.md
// section 10): this console's station ID, what the aircraft says this
// station is (in control, given control, backup, observing), and the two
// actions that move control: Hand over to backup, asked for with a
// Confirmation, and Take control, which resumes commanding and so is asked
// for where the console's command is held (CommandHoldBar), listing what
// the panels would change. It only shows StationControl and asks it; the
// aircraft decides.

#include <QWidget>

class QLabel;
class QLineEdit;
class QPushButton;
class StationControl;

class StationControlWidget : public QWidget {
    Q_OBJECT

public:
    explicit StationControlWidget(StationControl* control, QWidget* parent = nullptr);

    // The station as typed: "" for none (one station, control not followed).
    QString stationText() const;
    // Sets the field and, when it reads, the station.
    void setStationText(const QString& text);
    // The station can change only while no link runs: mid-link it would
    // change what the frames name.
    void setStationEditable(bool editable);

    QPushButton* handOverButton() const { return m_handOver; }
    QPushButton* takeControlButton() const { return m_takeControl; }
    QLabel* roleLabel() const { return m_role; }

public slots:
    // After the operator confirmed it in a dialog.
    void requestHandOver();

signals:
    // Take control was clicked while the aircraft names this station in
    // control: whoever holds the command asks and takes it.
    void takeControlRequested();
    // The typed station did not read: what is wrong, for the operator.
    void stationRefused(const QString& reason);

private:
    void readStation();
    void refresh();

    StationControl* m_control;
    QLineEdit* m_station;
    QLabel* m_role;
    QPushButton* m_handOver;
    QPushButton* m_takeControl;
};
