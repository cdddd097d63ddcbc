#pragma once

// The console's side of control between stations (docs/protocol.md section
// 10): from the station in control and the backup that the aircraft reports
// in its status frames, what this station is (in control, given control,
// backup, observing) and what its own frames must name as
// ID_GCS_destination and ID_GCS_backup. The aircraft decides who is in
// control; this only follows what it reports, and asks for a change when the
// operator confirms one (hand over, take control).
//
// No widgets and no I/O: ConsoleSession feeds it the status frames and
// applies it to every command it sends, so a headless session and the window
// behave the same.

#include "codec/message/Message.h"

#include <QObject>
#include <QString>

#include <optional>

class StationControl : public QObject {
    Q_OBJECT

public:
    enum class Role {
        Unknown,      // no status frame on this link yet
        InControl,    // the aircraft names this station in control, and its operator took control on this link
        Offered,      // the aircraft names this station in control; its operator has not taken it on this link
        HandingOver,  // asked the aircraft to give control to the backup
        Backup,       // the aircraft names this station its backup
        Observing,    // neither
    };
    Q_ENUM(Role)

    explicit StationControl(QObject* parent = nullptr);

    // This console's station ID. None: control is not followed, and the
    // command goes with the stations its header names (one station, as
    // before there were several).
    void setStation(std::optional<rcm::StationId> station);
    std::optional<rcm::StationId> station() const { return m_station; }

    Role role() const { return m_role; }
    // As the last status frame named them.
    std::optional<rcm::StationId> reportedControl() const { return m_reportedControl; }
    std::optional<rcm::StationId> reportedBackup() const { return m_reportedBackup; }

    // Writes what this station's frames name into `command`'s header; the
    // rest of the command is left as it is.
    void applyTo(rcm::Message& command) const;

    bool canHandOver() const;
    bool canTakeControl() const { return m_role == Role::Offered; }
    // For people: "In control", "Backup: GB_30226 in control", ...
    QString describe() const;
    static QString roleName(Role role);

public slots:
    // A status frame delivered from the aircraft.
    void statusReceived(const rcm::Message& status);
    // The operator confirmed: give control to the reported backup. Does
    // nothing unless canHandOver().
    void handOver();
    // The operator confirmed: command from now on. Does nothing unless canTakeControl().
    void takeControl();
    // The link ended: the role is unknown until the next status frame, and
    // the frames name no station meanwhile. Control is taken again only by
    // another Take control.
    void reset();

signals:
    void roleChanged(StationControl::Role role);
    // applyTo() writes something else from now on.
    void headerChanged();
    // Control moved without this station asking: a failover away from or to
    // it. Said once per change, with the reason for the operator and the log.
    void alarm(const QString& reason);
    // Control moved as this station asked, for the event log.
    void event(const QString& text);

private:
    void setRole(Role role);

    std::optional<rcm::StationId> m_station;
    std::optional<rcm::StationId> m_reportedControl;
    std::optional<rcm::StationId> m_reportedBackup;
    Role m_role = Role::Unknown;
    // The operator took control on this link (takeControl()) and the
    // aircraft has not named another station since: the frames claim control
    // (ID_GCS_destination and ID_GCS_backup both this station).
    bool m_claimed = false;
    // The aircraft last named this station in control: a new link that finds
    // another station in control is a failover away from it.
    bool m_heldControl = false;
};
