#include "ui/rehearsal/RehearsalDialog.h"

#include "link/rehearsal/ScenarioRunner.h"
#include "link/session/DataFolder.h"
#include "ui/rehearsal/RehearsalCommandLine.h"

#include <QDateTime>
#include <QDesktopServices>
#include <QDialogButtonBox>
#include <QDir>
#include <QFileDialog>
#include <QLabel>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QStandardPaths>
#include <QUrl>
#include <QVBoxLayout>

namespace {

// The progress bar counts tenths of a second of scenario time.
constexpr int kTicksPerSecond = 10;

}  // namespace

RehearsalDialog::RehearsalDialog(QWidget* parent)
    : QDialog(parent),
      m_title(new QLabel),
      m_progress(new QProgressBar),
      m_timeline(new QPlainTextEdit),
      m_verdict(new QLabel),
      m_openReport(new QPushButton(tr("Open report")))
{
    setWindowTitle(tr("Rehearsal"));
    m_timeline->setReadOnly(true);
    m_verdict->setWordWrap(true);
    m_verdict->setTextInteractionFlags(Qt::TextSelectableByMouse);
    m_openReport->setEnabled(false);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close);
    buttons->addButton(m_openReport, QDialogButtonBox::ActionRole);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    connect(m_openReport, &QPushButton::clicked, this, [this] {
        QDesktopServices::openUrl(QUrl::fromLocalFile(QDir(m_reportDirectory).filePath(QStringLiteral("report.html"))));
    });
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(m_title);
    layout->addWidget(m_progress);
    layout->addWidget(m_timeline, 1);
    layout->addWidget(m_verdict);
    layout->addWidget(buttons);
    resize(640, 480);
}

RehearsalDialog::~RehearsalDialog() = default;

void RehearsalDialog::chooseAndRun(QWidget* parent)
{
    const QString path =
        QFileDialog::getOpenFileName(parent, tr("Rehearse scenario"), DataFolder::path(QStringLiteral("scenarios")),
                                     tr("Rehearsal scenarios (*.json)"));
    if (path.isEmpty())
        return;
    const QString stamp = QDateTime::currentDateTimeUtc().toString(QStringLiteral("yyyy-MM-ddTHH-mm-ssZ"));
    const QString directory =
        QDir(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation))
            .filePath(QStringLiteral("rehearsals/%1-%2").arg(QFileInfo(path).completeBaseName(), stamp));
    auto* dialog = new RehearsalDialog(parent);
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    dialog->show();
    dialog->run(path, directory);
}

bool RehearsalDialog::run(const QString& scenarioPath, const QString& reportDirectory, double speed)
{
    m_runner.reset();
    m_timeline->clear();
    m_openReport->setEnabled(false);
    ScenarioError error;
    auto scenario = Scenario::load(scenarioPath, RehearsalCommandLine::planLoader(), &error);
    if (!scenario) {
        m_title->setText(tr("The scenario is wrong"));
        m_verdict->setText(error.text());
        return false;
    }
    m_reportDirectory = reportDirectory;
    QDir().mkpath(reportDirectory);
    m_title->setText(tr("%1 (%2 s of scenario time)").arg(scenario->name).arg(scenario->duration));
    m_progress->setRange(0, int(scenario->duration * kTicksPerSecond));
    m_progress->setValue(0);
    m_verdict->setText(tr("Running\u2026"));
    m_runner = std::make_unique<ScenarioRunner>(std::move(*scenario),
                                                QDir(reportDirectory).filePath(QStringLiteral("session.pcapng")));
    connect(m_runner.get(), &ScenarioRunner::progress, this, [this](double seconds, double) {
        m_progress->setValue(int(seconds * kTicksPerSecond));
        m_progress->setFormat(tr("%1 s").arg(int(seconds)));
    });
    connect(m_runner.get(), &ScenarioRunner::noted, this,
            [this](double seconds, const QString& kind, const QString& text) {
                m_timeline->appendPlainText(QStringLiteral("%1 s  %2  %3").arg(seconds, 6, 'f', 1).arg(kind, text));
            });
    connect(m_runner.get(), &ScenarioRunner::finished, this, &RehearsalDialog::runFinished);
    m_runner->start(speed);
    return true;
}

void RehearsalDialog::runFinished()
{
    const RehearsalReport& report = m_runner->report();
    QString error;
    const bool written = report.write(m_reportDirectory, &error);
    QString text = report.passed() ? tr("PASSED: %1.").arg(report.verdict()) : tr("FAILED: %1.").arg(report.verdict());
    for (const QString& failure : report.failures())
        text += QLatin1Char('\n') + failure;
    text += QLatin1Char('\n') + (written ? tr("Report in %1").arg(m_reportDirectory) : error);
    m_verdict->setText(text);
    m_openReport->setEnabled(written);
    emit finished();
}

QString RehearsalDialog::verdict() const
{
    return m_verdict->text();
}

QString RehearsalDialog::timeline() const
{
    return m_timeline->toPlainText();
}

int RehearsalDialog::progressValue() const
{
    return m_progress->value();
}

int RehearsalDialog::progressMaximum() const
{
    return m_progress->maximum();
}
