#include "ui/window/LinkSettingsWidget.h"

#include "link/transport/ModemProfile.h"
#include "link/transport/SerialLink.h"
#include "ui/panels/DeliberateInput.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QIntValidator>
#include <QRegularExpression>
#include <QRegularExpressionValidator>
#include <QLineEdit>
#include <QSpinBox>
#include <QStackedWidget>
#include <QStyle>
#include <QToolButton>
#include <QVBoxLayout>

namespace {

QSpinBox* portBox(int minimum, const QString& special = {})
{
    auto* box = new QSpinBox;
    box->setRange(minimum, 65535);
    if (!special.isEmpty())
        box->setSpecialValueText(special);
    return box;
}

QFormLayout* form(QWidget* page)
{
    auto* layout = new QFormLayout(page);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
    return layout;
}

}  // namespace

LinkSettingsWidget::LinkSettingsWidget(QWidget* parent)
    : QWidget(parent),
      m_transport(new QComboBox),
      m_pages(new QStackedWidget),
      m_port(new QComboBox),
      m_refresh(new QToolButton),
      m_baud(new QComboBox),
      m_dialNumber(new QLineEdit),
      m_modemInit(new QLineEdit),
      m_modemProfile(new QComboBox),
      m_currency(new QLineEdit),
      m_rtsCts(new QCheckBox(tr("RTS/CTS flow control"))),
      m_callCost(new QDoubleSpinBox),
      m_satelliteDelay(new QSpinBox),
      m_localAddress(new QLineEdit),
      m_localPort(portBox(0, tr("any"))),
      m_remoteAddress(new QLineEdit),
      m_remotePort(portBox(1)),
      m_keyPath(new QLineEdit),
      m_chooseKey(new QToolButton)
{
    m_transport->addItem(tr("UDP"), int(LinkSettings::Transport::Udp));
    m_transport->addItem(tr("Serial modem"), int(LinkSettings::Transport::Serial));
    m_transport->setToolTip(tr("UDP: one 510-byte datagram a frame. Serial: 600-byte frames in the byte stream."));
    m_pages->addWidget(udpPage());
    m_pages->addWidget(serialPage());

    auto* layout = new QFormLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
    layout->addRow(tr("Transport"), m_transport);
    layout->addRow(m_pages);
    layout->addRow(tr("Key file"), keyRow());
    connectChanges();
    setSettings(LinkSettings());
}

QWidget* LinkSettingsWidget::udpPage()
{
    auto* udpPage = new QWidget;
    QFormLayout* udp = form(udpPage);
    m_remoteAddress->setToolTip(tr("IP address of the aircraft's link"));
    m_remotePort->setToolTip(tr("UDP port of the aircraft's link, 1..65535"));
    m_localAddress->setToolTip(tr("Local address to receive on; 0.0.0.0 for every interface"));
    m_localPort->setToolTip(tr("Local UDP port, 0..65535; \"any\" lets the system choose"));
    auto* remote = new QHBoxLayout;
    remote->addWidget(m_remoteAddress, 1);
    remote->addWidget(m_remotePort);
    auto* local = new QHBoxLayout;
    local->addWidget(m_localAddress, 1);
    local->addWidget(m_localPort);
    udp->addRow(tr("Aircraft"), remote);
    udp->addRow(tr("Local"), local);
    return udpPage;
}

QWidget* LinkSettingsWidget::serialPage()
{
    auto* serialPage = new QWidget;
    QFormLayout* serial = form(serialPage);
    m_port->setEditable(true);
    m_port->setInsertPolicy(QComboBox::NoInsert);
    m_port->setToolTip(tr("Serial port of the radio modem; a path such as /dev/pts/3 may be typed"));
    m_port->lineEdit()->setPlaceholderText(tr("no port found"));
    m_refresh->setIcon(style()->standardIcon(QStyle::SP_BrowserReload));
    m_refresh->setToolTip(tr("List the serial ports again"));
    for (int rate : {1200, 2400, 4800, 9600, 19200, 38400, 57600, 115200})
        m_baud->addItem(QString::number(rate), rate);
    m_baud->setEditable(true);
    m_baud->setValidator(new QIntValidator(1, 4000000, m_baud));
    m_baud->setToolTip(tr("Bit rate, 8N1; the modem's is 9600 bit/s"));
    auto* port = new QHBoxLayout;
    port->addWidget(m_port, 1);
    port->addWidget(m_refresh);
    serial->addRow(tr("Port"), port);
    serial->addRow(tr("Bit rate"), m_baud);
    addModemRows(serial);
    return serialPage;
}

void LinkSettingsWidget::addModemRows(QFormLayout* serial)
{
    m_dialNumber->setPlaceholderText(tr("none: the line is connected"));
    m_dialNumber->setClearButtonEnabled(true);
    m_dialNumber->setValidator(new QRegularExpressionValidator(QRegularExpression(QStringLiteral("[0-9+*#,PTpt ]*")),
                                                                m_dialNumber));
    m_dialNumber->setToolTip(tr("A satellite phone's modem: the aircraft's number, dialled with ATD; a dropped call "
                                "is redialled, and Disconnect or Quit hangs up (docs/modem.md)"));
    m_modemInit->setToolTip(tr("Sent to the modem before dialling; it must start with AT and keep verbose "
                               "result codes (V1). Check the phone's manual for its own settings."));
    m_rtsCts->setToolTip(tr("Hardware flow control: the modem stops the console (CTS) when its buffer is full, "
                            "instead of losing bytes. On for a modem; off only for a cable without the lines."));
    m_callCost->setRange(0, 1000);
    m_callCost->setDecimals(2);
    m_callCost->setSpecialValueText(tr("not shown"));
    m_callCost->setToolTip(tr("The call's price per started minute, shown with its currency when a call ends"));
    m_currency->setMaxLength(8);
    m_currency->setPlaceholderText(tr("currency"));
    m_currency->setToolTip(tr("The currency of the price, such as USD or EUR"));
    m_currency->setMaximumWidth(fontMetrics().horizontalAdvance(QStringLiteral("MMMMMM")));
    for (const modem::Profile& profile : modem::profiles()) {
        m_modemProfile->addItem(profile.title, profile.name);
        m_modemProfile->setItemData(m_modemProfile->count() - 1, profile.note, Qt::ToolTipRole);
    }
    m_modemProfile->setToolTip(tr("The satellite phone: its data bearer, and how it tells its registration and "
                                  "signal; the console dials only once the phone is registered, with signal "
                                  "(docs/modem.md)"));
    serial->addRow(tr("Dial"), m_dialNumber);
    serial->addRow(tr("Phone"), m_modemProfile);
    serial->addRow(tr("Modem init"), m_modemInit);
    serial->addRow(QString(), m_rtsCts);
    auto* cost = new QHBoxLayout;
    cost->addWidget(m_callCost, 1);
    cost->addWidget(m_currency);
    serial->addRow(tr("Cost a minute"), cost);
    m_satelliteDelay->setRange(0, 10000);
    m_satelliteDelay->setSingleStep(100);
    m_satelliteDelay->setSuffix(tr(" ms"));
    m_satelliteDelay->setToolTip(tr("The satellite's delay one way: a reported value is called a mismatch only "
                                    "once twice this and a frame's airtime (0.5 s) have passed since the command "
                                    "changed"));
    serial->addRow(tr("Delay, one way"), m_satelliteDelay);
}

QLayout* LinkSettingsWidget::keyRow()
{
    // The same key file for either transport: it belongs to the aircraft.
    m_keyPath->setPlaceholderText(tr("none"));
    m_keyPath->setClearButtonEnabled(true);
    m_keyPath->setToolTip(
        tr("The aircraft's key file (64 hex digits, mode 0600, made by rcm keygen) for a link that is "
           "encrypted and authenticated; empty for the plain link. Only the path is remembered."));
    m_chooseKey->setText(QStringLiteral("\u2026"));
    m_chooseKey->setToolTip(tr("Choose the aircraft's key file"));
    auto* key = new QHBoxLayout;
    key->addWidget(m_keyPath, 1);
    key->addWidget(m_chooseKey);
    return key;
}

void LinkSettingsWidget::connectChanges()
{
    connect(m_transport, &QComboBox::currentIndexChanged, this, [this](int index) {
        showPage(index);
        if (index == 1 && m_port->count() == 0)
            refreshPorts();
        emit changed();
    });
    connect(m_refresh, &QToolButton::clicked, this, &LinkSettingsWidget::refreshPorts);
    connect(m_chooseKey, &QToolButton::clicked, this, &LinkSettingsWidget::chooseKeyFile);
    connect(m_modemProfile, &QComboBox::currentIndexChanged, this, &LinkSettingsWidget::changed);
    for (QLineEdit* edit : {m_localAddress, m_remoteAddress, m_keyPath, m_dialNumber, m_modemInit, m_currency})
        connect(edit, &QLineEdit::textChanged, this, &LinkSettingsWidget::changed);
    for (QSpinBox* box : {m_localPort, m_remotePort, m_satelliteDelay})
        connect(box, &QSpinBox::valueChanged, this, &LinkSettingsWidget::changed);
    connect(m_port, &QComboBox::currentTextChanged, this, &LinkSettingsWidget::changed);
    connect(m_baud, &QComboBox::currentTextChanged, this, &LinkSettingsWidget::changed);
    connect(m_rtsCts, &QCheckBox::toggled, this, &LinkSettingsWidget::changed);
    connect(m_callCost, &QDoubleSpinBox::valueChanged, this, &LinkSettingsWidget::changed);
    // A wheel turned over the pane to scroll it must not switch the
    // transport or move a port: the link settings change only by hand.
    for (QWidget* control : std::initializer_list<QWidget*>{m_transport, m_port, m_baud, m_localPort, m_remotePort, m_callCost, m_satelliteDelay, m_modemProfile})
        DeliberateInput::protect(control);
}

LinkSettings LinkSettingsWidget::settings() const
{
    LinkSettings s;
    s.transport = LinkSettings::Transport(m_transport->currentData().toInt());
    // The list shows "ttyUSB0 - FTDI cable"; the port is the first word.
    const QString port = m_port->currentText().trimmed();
    const int index = m_port->findText(port);
    s.serialPort = index >= 0 ? m_port->itemData(index).toString() : port;
    s.baudRate = m_baud->currentText().toInt();
    s.localAddress = m_localAddress->text().trimmed();
    s.localPort = quint16(m_localPort->value());
    s.remoteAddress = m_remoteAddress->text().trimmed();
    s.remotePort = quint16(m_remotePort->value());
    s.keyPath = m_keyPath->text().trimmed();
    s.dialNumber = m_dialNumber->text().trimmed();
    s.modemInit = m_modemInit->text().trimmed();
    s.modemProfile = m_modemProfile->currentData().toString();
    s.callCurrency = m_currency->text().trimmed();
    s.rtsCts = m_rtsCts->isChecked();
    s.callCostPerMinute = m_callCost->value();
    s.satelliteDelayMs = m_satelliteDelay->value();
    return s;
}

void LinkSettingsWidget::setSettings(const LinkSettings& s)
{
    m_transport->setCurrentIndex(m_transport->findData(int(s.transport)));
    showPage(m_transport->currentIndex());
    const int port = m_port->findData(s.serialPort);
    if (port >= 0)
        m_port->setCurrentIndex(port);
    else
        m_port->setEditText(s.serialPort);
    m_baud->setEditText(QString::number(s.baudRate));
    m_localAddress->setText(s.localAddress);
    m_localPort->setValue(s.localPort);
    m_remoteAddress->setText(s.remoteAddress);
    m_remotePort->setValue(s.remotePort);
    m_keyPath->setText(s.keyPath);
    m_dialNumber->setText(s.dialNumber);
    m_modemInit->setText(s.modemInit);
    const int profile = m_modemProfile->findData(s.modemProfile);
    m_modemProfile->setCurrentIndex(profile >= 0 ? profile : 0);
    m_currency->setText(s.callCurrency);
    m_rtsCts->setChecked(s.rtsCts);
    m_callCost->setValue(s.callCostPerMinute);
    m_satelliteDelay->setValue(s.satelliteDelayMs);
}

void LinkSettingsWidget::showPage(int index)
{
    // A stacked widget is as tall as its tallest page; the UDP page must not
    // keep the serial page's modem rows as blank space under it.
    for (int i = 0; i < m_pages->count(); ++i) {
        const QSizePolicy::Policy policy = i == index ? QSizePolicy::Preferred : QSizePolicy::Ignored;
        m_pages->widget(i)->setSizePolicy(policy, policy);
    }
    m_pages->setCurrentIndex(index);
    m_pages->updateGeometry();
}

void LinkSettingsWidget::chooseKeyFile()
{
    const QString current = m_keyPath->text().trimmed();
    const QString path = QFileDialog::getOpenFileName(
        this, tr("The aircraft's key file"), current.isEmpty() ? QDir::homePath() : QFileInfo(current).absolutePath(),
        tr("Key files (*.key);;All files (*)"));
    if (!path.isEmpty())
        m_keyPath->setText(QDir::toNativeSeparators(path));
}

void LinkSettingsWidget::refreshPorts()
{
    const QString chosen = settings().serialPort;
    m_port->clear();
    for (const auto& info : SerialLink::availablePorts()) {
        const QString description = info.description().isEmpty()
                                        ? info.portName()
                                        : info.portName() + QStringLiteral(" \u2013 ") + info.description();
        m_port->addItem(description, info.portName());
    }
    const int index = m_port->findData(chosen);
    if (index >= 0)
        m_port->setCurrentIndex(index);
    else
        m_port->setEditText(chosen);
}
