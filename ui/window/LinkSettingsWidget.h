#pragma once

// Edits LinkSettings: the transport, then either the serial port (from the
// system's list, refreshed on demand through SerialLink's helper, or typed,
// e.g. a pseudo-terminal), bit rate and, for a satellite phone's modem, the
// number to dial, the init string, RTS/CTS and the call's price a minute,
// or the UDP endpoints; and, for either,
// the aircraft's key file (typed, or chosen in a file dialog) for a secure link.

#include "link/session/LinkSettings.h"

#include <QWidget>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLineEdit;
class QSpinBox;
class QStackedWidget;
class QToolButton;
class QFormLayout;
class QLayout;

class LinkSettingsWidget : public QWidget {
    Q_OBJECT

public:
    explicit LinkSettingsWidget(QWidget* parent = nullptr);

    LinkSettings settings() const;
    void setSettings(const LinkSettings& settings);

    QLineEdit* keyPathEdit() const { return m_keyPath; }

public slots:
    // Lists the serial ports again, keeping the one chosen.
    void refreshPorts();
    // A file dialog for the key file.
    void chooseKeyFile();

signals:
    void changed();

private:
    QWidget* udpPage();
    QWidget* serialPage();
    // The satellite phone's: the number, the phone, its init string, flow
    // control, the call's cost and the satellite's delay.
    void addModemRows(QFormLayout* serial);
    QLayout* keyRow();
    // Every edit says changed(); none changes by a wheel turned over it.
    void connectChanges();
    void showPage(int index);

    QComboBox* m_transport;
    QStackedWidget* m_pages;
    QComboBox* m_port;
    QToolButton* m_refresh;
    QComboBox* m_baud;
    QLineEdit* m_dialNumber;
    QLineEdit* m_modemInit;
    QComboBox* m_modemProfile;
    QLineEdit* m_currency;
    QCheckBox* m_rtsCts;
    QDoubleSpinBox* m_callCost;
    QSpinBox* m_satelliteDelay;
    QLineEdit* m_localAddress;
    QSpinBox* m_localPort;
    QLineEdit* m_remoteAddress;
    QSpinBox* m_remotePort;
    QLineEdit* m_keyPath;
    QToolButton* m_chooseKey;
};
