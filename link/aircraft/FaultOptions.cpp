#include "link/aircraft/FaultOptions.h"

#include <QCommandLineParser>
#include <QStringList>

#include <cmath>

namespace {

// A probability option's value, 0..1; null when it is not one.
std::optional<double> probability(const QString& text)
{
    bool ok = false;
    const double p = text.toDouble(&ok);
    if (!ok || p < 0 || p > 1)
        return std::nullopt;
    return p;
}

}  // namespace

bool parseNumberPair(const QString& text, double* a, double* b)
{
    const QStringList p = text.split(QLatin1Char(':'));
    if (p.size() != 2)
        return false;
    bool okA = false, okB = false;
    *a = p[0].toDouble(&okA);
    *b = p[1].toDouble(&okB);
    return okA && okB && *a >= 0 && *b >= 0;
}

FaultOptions::FaultOptions()
    : m_ber(QStringLiteral("ber"), QStringLiteral("Fault: flip each bit sent with probability <rate>."),
            QStringLiteral("rate")),
      m_burst(QStringLiteral("burst"),
              QStringLiteral("Fault: error bursts <len> bits long, <rate> per frame on average (Poisson)."),
              QStringLiteral("len:rate")),
      m_drop(QStringLiteral("drop"), QStringLiteral("Fault: lose each status frame with probability <p>."),
             QStringLiteral("p")),
      m_delay(QStringLiteral("delay"), QStringLiteral("Fault: send each status frame <ms> milliseconds late."),
              QStringLiteral("ms")),
      m_outage(QStringLiteral("outage"),
               QStringLiteral("Fault: <start> seconds after starting, for <duration> seconds, send and receive "
                              "nothing."),
               QStringLiteral("start:duration")),
      m_silent(QStringLiteral("silent"),
               QStringLiteral("Fault: stop replying (commands are still received and acted on).")),
      m_seed(QStringLiteral("seed"), QStringLiteral("Seed of the fault generator, so a rehearsal repeats (default 1)."),
             QStringLiteral("n"), QStringLiteral("1"))
{
}

void FaultOptions::addTo(QCommandLineParser& parser) const
{
    parser.addOptions({m_ber, m_burst, m_drop, m_delay, m_outage, m_silent, m_seed});
}

std::optional<FaultSettings> FaultOptions::read(const QCommandLineParser& parser, QString* error) const
{
    FaultSettings faults;
    const auto wrong = [&](const QString& message) {
        *error = message;
        return std::nullopt;
    };
    if (parser.isSet(m_ber)) {
        const auto p = probability(parser.value(m_ber));
        if (!p)
            return wrong(QStringLiteral("--ber wants a probability 0..1, not %1").arg(parser.value(m_ber)));
        faults.bitErrorRate = *p;
    }
    if (parser.isSet(m_burst)) {
        double length = 0, rate = 0;
        if (!parseNumberPair(parser.value(m_burst), &length, &rate))
            return wrong(QStringLiteral("--burst wants LEN:RATE, e.g. 32:0.5, not %1").arg(parser.value(m_burst)));
        faults.burstLength = static_cast<std::size_t>(length);
        faults.burstRate = rate;
    }
    if (parser.isSet(m_drop)) {
        const auto p = probability(parser.value(m_drop));
        if (!p)
            return wrong(QStringLiteral("--drop wants a probability 0..1, not %1").arg(parser.value(m_drop)));
        faults.dropProbability = *p;
    }
    bool ok = true;
    if (parser.isSet(m_delay)) {
        const int ms = parser.value(m_delay).toInt(&ok);
        if (!ok || ms < 0)
            return wrong(QStringLiteral("--delay wants milliseconds, not %1").arg(parser.value(m_delay)));
        faults.delay = std::chrono::milliseconds(ms);
    }
    if (parser.isSet(m_outage)) {
        double start = 0, duration = 0;
        if (!parseNumberPair(parser.value(m_outage), &start, &duration))
            return wrong(
                QStringLiteral("--outage wants START:DURATION in seconds, not %1").arg(parser.value(m_outage)));
        faults.outageStart = std::chrono::milliseconds(std::llround(start * 1000));
        faults.outageDuration = std::chrono::milliseconds(std::llround(duration * 1000));
    }
    faults.silent = parser.isSet(m_silent);
    faults.seed = parser.value(m_seed).toULongLong(&ok);
    if (!ok)
        return wrong(QStringLiteral("--seed wants a whole number, not %1").arg(parser.value(m_seed)));
    return faults;
}

QString FaultOptions::countersText(const FaultInjector::Counters& n)
{
    return QStringLiteral(
               "faults: %1 frames offered, %2 sent (%3 damaged, %4 bits flipped, %5 bursts), %6 dropped, "
               "%7 lost to the outage, %8 silenced; %9 arrivals lost to the outage")
        .arg(n.framesOffered)
        .arg(n.framesSent)
        .arg(n.framesDamaged)
        .arg(n.bitsFlipped)
        .arg(n.bursts)
        .arg(n.framesDropped)
        .arg(n.framesLostToOutage)
        .arg(n.framesSilenced)
        .arg(n.framesNotReceived);
}
