// Measures how close to its tick each frame leaves: the floor is "within
// 50 ms of its tick". A LinkController at the default one-second cadence
// sends to a far end in this thread, over UDP on loopback or over a
// pseudo-terminal. Two figures per frame:
//   write:   ideal tick -> frame handed to the transport, as the worker
//            records it (LinkStatistics::sendDelay*)
//   arrival: the UTC second -> the frame's first byte read by the far end,
//            which adds the kernel and this thread's wake-up
//
//   bench_cadence [ticks] [--pty]      (default: 60 ticks over UDP)

#include "Spread.h"
#include "link/session/LinkController.h"
#include "link/transport/SerialLink.h"
#include "link/transport/UdpLink.h"

#include <QCoreApplication>
#include <QSocketNotifier>
#include <QTimer>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fcntl.h>
#include <pty.h>
#include <unistd.h>
#include <vector>

namespace {

std::int64_t utcMicrosNow()
{
    using namespace std::chrono;
    return duration_cast<microseconds>(system_clock::now().time_since_epoch()).count();
}

}  // namespace

int main(int argc, char** argv)
{
    QCoreApplication app(argc, argv);
    int ticks = 60;
    bool overPty = false;
    for (const QString& arg : app.arguments().mid(1)) {
        if (arg == QLatin1String("--pty"))
            overPty = true;
        else
            ticks = std::max(1, arg.toInt());
    }

    std::vector<std::int64_t> arrivals;  // micros after the UTC second
    std::int64_t lastArrival = 0;
    // A frame's first byte: the first read after a quiet half second.
    const auto arrived = [&] {
        const std::int64_t now = utcMicrosNow();
        if (now - lastArrival > 500000)
            arrivals.push_back(now % 1000000);
        lastArrival = now;
    };

    std::unique_ptr<Link> link;
    UdpLink farUdp(QHostAddress::LocalHost, 0);
    int master = -1;
    int slave = -1;
    std::unique_ptr<QSocketNotifier> notifier;
    if (overPty) {
        char name[256] = {};
        if (::openpty(&master, &slave, name, nullptr, nullptr) != 0) {
            std::perror("openpty");
            return 1;
        }
        ::fcntl(master, F_SETFL, ::fcntl(master, F_GETFL) | O_NONBLOCK);
        notifier = std::make_unique<QSocketNotifier>(master, QSocketNotifier::Read);
        QObject::connect(notifier.get(), &QSocketNotifier::activated, [&] {
            char buffer[4096];
            if (::read(master, buffer, sizeof buffer) > 0)
                arrived();
        });
        link = std::make_unique<SerialLink>(QString::fromLocal8Bit(name));
    } else {
        farUdp.open();
        QObject::connect(&farUdp, &Link::datagramReceived, arrived);
        link = std::make_unique<UdpLink>(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, farUdp.boundPort());
    }

    LinkController controller(std::move(link));  // default options: 1000 ms ticks on the second
    rcm::Message command;
    command.header.set(rcm::ItemId::ID_UA_source, rcm::Value::pair(44, 133));
    command.header.set(rcm::ItemId::ID_GCS_destination, rcm::Value::pair(44, 2));
    controller.setCommand(command);
    QObject::connect(&controller, &LinkController::errorOccurred,
                     [](const QString& message) { std::fprintf(stderr, "%s\n", qPrintable(message)); });
    QObject::connect(&controller, &LinkController::statisticsChanged, [&](const LinkStatistics& s) {
        if (s.sendDelaySamples >= quint64(ticks) && int(arrivals.size()) >= ticks)
            app.quit();
    });
    controller.start();
    std::printf("%d ticks over %s, about %d s\n", ticks, overPty ? "a pseudo-terminal" : "UDP loopback", ticks + 1);
    app.exec();

    const LinkStatistics s = controller.statistics();
    std::printf("write    n=%llu  min %.3f ms  max %.3f ms  mean %.3f ms  (ticks missed %llu)\n",
                static_cast<unsigned long long>(s.sendDelaySamples), double(s.sendDelayMinMicros) / 1000.0,
                double(s.sendDelayMaxMicros) / 1000.0, s.sendDelayMeanMicros() / 1000.0,
                static_cast<unsigned long long>(s.ticksMissed));
    rcm::bench::printSpread("arrival", arrivals, 0.99, 3);
    if (master >= 0) {
        notifier.reset();
        ::close(master);
        ::close(slave);
    }
    return 0;
}
