#include "ui/plan/FlightPlanUpload.h"

#include "codec/secure/SecureCodec.h"

#include <QMutexLocker>
#include <QRandomGenerator>

#include <algorithm>
#include <stdexcept>

namespace {

// Sections a new measurement is averaged over: enough to smooth one late
// frame, few enough that a link that slows down shows it within a minute.
constexpr double kRateSmoothing = 8;

}  // namespace

double FlightPlanUpload::Progress::secondsLeftInPass(double nominal) const
{
    const double perSection = rateMeasured ? secondsPerSection : nominal;
    return std::max(total - (pass == 0 ? 0 : inPass), 0) * perSection;
}

double FlightPlanUpload::Progress::secondsLeftAtMost(double nominal) const
{
    const double perSection = rateMeasured ? secondsPerSection : nominal;
    const int passesAfterThis = std::max(maxPasses - std::max(pass, 1), 0);
    return secondsLeftInPass(nominal) + double(passesAfterThis) * total * perSection;
}

FlightPlanUpload::FlightPlanUpload(QObject* parent) : QObject(parent)
{
    qRegisterMetaType<FlightPlanUpload::Progress>();
    m_clock.start();
}

FlightPlanUpload::~FlightPlanUpload() = default;

bool FlightPlanUpload::start(const QByteArray& plan, QString* error)
{
    Progress progress;
    {
        QMutexLocker lock(&m_mutex);
        // A new ID for every upload: the aircraft takes a section with an ID
        // it holds as part of the plan it holds, so an edited plan sent under
        // the old ID could be mixed with the old one.
        quint32 id = 0;
        while (id == 0 || id == m_lastPlanId)
            id = QRandomGenerator::global()->generate();
        try {
            m_uploader = std::make_unique<rcm::FlightPlanUploader>(
                id,
                std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(plan.constData()),
                                              std::size_t(plan.size())),
                m_sectionSize, kMaxPasses);
        } catch (const std::invalid_argument& e) {
            if (error)
                *error = QString::fromStdString(e.what());
            return false;
        }
        m_lastPlanId = id;
        m_state = State::Sending;
        m_lastSectionNs = -1;
        progress = progressLocked();
    }
    emit progressChanged(progress);
    return true;
}

void FlightPlanUpload::cancel()
{
    Progress progress;
    {
        QMutexLocker lock(&m_mutex);
        if (m_state != State::Sending)
            return;
        m_state = State::Cancelled;
        progress = progressLocked();
        m_uploader.reset();
    }
    emit progressChanged(progress);
}

int FlightPlanUpload::sectionSize() const
{
    QMutexLocker lock(&m_mutex);
    return int(m_sectionSize);
}

FlightPlanUpload::Progress FlightPlanUpload::progress() const
{
    QMutexLocker lock(&m_mutex);
    return progressLocked();
}

FlightPlanUpload::Progress FlightPlanUpload::progressLocked() const
{
    Progress p;
    p.state = m_state;
    if (m_uploader) {
        const rcm::FlightPlanUploader::Progress u = m_uploader->progress();
        p.planId = m_uploader->planId();
        p.sent = int(u.sent);
        p.total = int(u.total);
        p.inPass = int(u.inPass);
        p.pass = u.pass;
        p.maxPasses = u.maxPasses;
        p.rateMeasured = m_rateMeasured;
        p.secondsPerSection = m_secondsPerSection;
        const auto& report = m_uploader->acknowledgedReport();
        p.report = QByteArray(reinterpret_cast<const char*>(report.data()), qsizetype(report.size()));
    }
    return p;
}

LinkWorker::Options FlightPlanUpload::linkOptions(LinkWorker::Options options)
{
    {
        QMutexLocker lock(&m_mutex);
        m_sectionSize = options.secure ? rcm::secure::kMaxFlightPlanData : rcm::FlightPlanSection::kMaxData;
    }
    options.block2Source = [this] { return next(); };
    options.block2Reply = [this](const rcm::FlightPlanSection& reply) { handleReply(reply); };
    return options;
}

std::optional<rcm::FlightPlanSection> FlightPlanUpload::next()
{
    std::optional<rcm::FlightPlanSection> section;
    Progress progress;
    {
        QMutexLocker lock(&m_mutex);
        if (!m_uploader || m_state != State::Sending)
            return std::nullopt;
        section = m_uploader->next();
        if (section)
            measureSection();
        if (m_uploader->state() == rcm::FlightPlanUploader::State::GaveUp)
            m_state = State::GaveUp;
        progress = progressLocked();
    }
    emit progressChanged(progress);
    return section;
}

void FlightPlanUpload::handleReply(const rcm::FlightPlanSection& reply)
{
    Progress progress;
    {
        QMutexLocker lock(&m_mutex);
        if (!m_uploader || m_state != State::Sending || !m_uploader->handleReply(reply))
            return;
        m_state = State::Acknowledged;
        progress = progressLocked();
    }
    emit progressChanged(progress);
}

void FlightPlanUpload::measureSection()
{
    const qint64 now = m_clock.nsecsElapsed();
    if (m_lastSectionNs >= 0) {
        const double seconds = double(now - m_lastSectionNs) / 1e9;
        m_secondsPerSection =
            m_rateMeasured ? m_secondsPerSection + (seconds - m_secondsPerSection) / kRateSmoothing : seconds;
        m_rateMeasured = true;
    }
    m_lastSectionNs = now;
}
