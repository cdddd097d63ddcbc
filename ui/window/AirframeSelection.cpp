#include "ui/window/AirframeSelection.h"

#include "codec/message/CommandChanges.h"
#include "link/session/ConsoleSession.h"
#include "link/airframe/AirframeLoader.h"
#include "ui/alerts/Confirmation.h"
#include "ui/alerts/ConsoleAlerts.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/ItemText.h"

#include <QActionGroup>
#include <QFileDialog>
#include <QMenu>

AirframeSelection::AirframeSelection(CommandState* command, ConsoleSession* session, const ConsoleNotices& notices,
                                     QWidget* window)
    : QObject(window), m_command(command), m_session(session), m_notices(notices), m_window(window)
{
}

void AirframeSelection::addMenu(QMenu* file)
{
    QMenu* airframes = file->addMenu(tr("&Airframe"));
    m_actions = new QActionGroup(this);
    for (const QString& path : AirframeLoader::builtIn()) {
        const auto airframe = AirframeLoader::load(path);
        QAction* a = airframes->addAction(airframe ? QString::fromStdString(airframe->name) : path);
        a->setCheckable(true);
        a->setData(path);
        m_actions->addAction(a);
        connect(a, &QAction::triggered, this, [this, path] { request(path); });
    }
    airframes->addSeparator();
    airframes->addAction(tr("From a &file\u2026"), this, &AirframeSelection::choose);
}

bool AirframeSelection::load(const QString& path, QString* error)
{
    QString reason;
    const std::optional<rcm::Airframe> airframe = AirframeLoader::load(path, &reason);
    if (!airframe) {
        if (error)
            *error = reason;
        else
            m_notices.error(reason);
        return false;
    }
    const QString was = QString::fromStdString(m_command->airframe().name);
    const bool live = m_session->isLive();
    // Another airframe on a live link: nothing goes out until the aircraft's
    // report is in the panels and the operator resumes.
    if (live)
        m_session->holdCommand(CommandHold::Reason::Airframe);
    m_path = path;
    const std::vector<rcm::Unit> left = m_command->setAirframe(*airframe);
    tick();
    if (live || !left.empty()) {
        ConsoleAlerts* alerts = m_notices.alerts();
        const QString name = QString::fromStdString(airframe->name);
        alerts->info(EventSource::Console,
                     tr("Airframe %1 (was %2): the command's values carried over unit by unit").arg(name, was));
        if (!left.empty())
            alerts->warning(EventSource::Console,
                            tr("Not in airframe %1, so no longer commanded: %2").arg(name, ItemText::unitNames(left)));
    }
    return true;
}

void AirframeSelection::tick()
{
    if (!m_actions)
        return;
    for (QAction* a : m_actions->actions())
        a->setChecked(a->data().toString() == m_path);
}

void AirframeSelection::request(const QString& path)
{
    QString reason;
    const std::optional<rcm::Airframe> airframe = AirframeLoader::load(path, &reason);
    if (!airframe) {
        m_notices.error(reason);
        tick();
        return;
    }
    if (m_session->isLive()) {
        const std::vector<rcm::Unit> left = rcm::unitsMissingFrom(m_command->message(), rcm::restingCommand(*airframe));
        Confirmation ask;
        ask.title = tr("Airframe");
        ask.text = tr("Load the airframe %1 while the link is live?").arg(QString::fromStdString(airframe->name));
        ask.informativeText =
            tr("The command's values are carried over unit by unit. The console then holds the command back until "
               "the aircraft's report is in the panels and you resume commanding.") +
            (left.empty() ? QString()
                          : QLatin1Char('\n') +
                                tr("Not in this airframe, so no longer commanded: %1").arg(ItemText::unitNames(left)));
        ask.action = tr("Load airframe");
        if (!ask.ask(m_window)) {
            tick();
            return;
        }
    }
    load(path);
}

void AirframeSelection::choose()
{
    const QString path = QFileDialog::getOpenFileName(m_window, tr("Open an airframe"), QString(),
                                                      tr("Airframes (*.json);;All files (*)"));
    if (!path.isEmpty())
        request(path);
}
