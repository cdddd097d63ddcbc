#pragma once

// The fleet on screen: a line naming the broker and its state (connected,
// unreachable since when: the broker's state, apart from any link's) and
// counting the aircraft, and the table of aircraft sorted by name, their
// last frame's age kept current once a second. Aircraft that no trusted
// station reports are unverified: hidden unless "Show unverified" is ticked,
// and counted either way. Double-click or Enter on an aircraft asks for it
// to be observed (the console opens it read-only); the view itself opens
// nothing.

#include "ui/table/TablePane.h"

#include <QTimer>

class FleetModel;
class QCheckBox;
class QLabel;
class QSortFilterProxyModel;

class FleetView : public TablePane {
    Q_OBJECT

public:
    explicit FleetView(FleetModel* model, QWidget* parent = nullptr);

    // Ticks once a second while the view is shown: FleetModel::refreshAges().
    const QTimer& ageTimer() const { return m_ageTimer; }

    // The broker the rows come from, for the line above them ("mqtt://host:1883").
    void setBroker(const QString& broker);
    // Connected, or not; `sinceUtcMicros` when it went (0: now).
    void setBrokerConnected(bool connected, qint64 sinceUtcMicros = 0);
    // Messages the feed refused so far (forged, replayed ...).
    void setRefusedMessages(quint64 count);
    // "Broker mqtt://127.0.0.1:1883, connected: 3 aircraft, 1 stale, 1 offline"
    // "Broker mqtt://..., unreachable since 12:00:03 UTC: 3 aircraft, 2 unknown;
    //  4 unverified hidden; 12 messages refused"
    QString summaryText() const;
    QCheckBox* showUnverified() const { return m_showUnverified; }

signals:
    // Double-click or Enter on an aircraft's row.
    void observeRequested(const QString& aircraft);

protected:
    void showEvent(QShowEvent* event) override;
    void hideEvent(QHideEvent* event) override;

private:
    void updateSummary();

    FleetModel* m_model;
    QSortFilterProxyModel* m_sorted;
    QLabel* m_summary;
    QCheckBox* m_showUnverified;
    QTimer m_ageTimer;
    QString m_broker;
    bool m_connected = false;
    bool m_everConnected = false;
    qint64 m_lostUtcMicros = 0;
    quint64 m_refused = 0;
};
