#pragma once

// A frame log written out as CSV (exportFrameLogCsv) in a thread of its own:
// a day's log takes seconds, and the console keeps sending and drawing
// meanwhile. finished() comes back in the thread that started it; the
// export then deletes itself.

#include <QObject>
#include <QString>

#include <memory>

namespace rcm {
class LogKey;
}

class FrameLogCsvExport : public QObject {
    Q_OBJECT

public:
    // Exports `source` to `target` (written whole or not at all). With the
    // log's `key` (HCTR2 is safe from several threads), a keyed session's
    // frames export as their items, not as "enciphered".
    static FrameLogCsvExport* start(const QString& source, const QString& target,
                                    std::shared_ptr<const rcm::LogKey> key, QObject* parent = nullptr);

    QString target() const { return m_target; }

signals:
    // Written, or not and why.
    void finished(bool written, const QString& error);

private:
    FrameLogCsvExport(const QString& target, QObject* parent) : QObject(parent), m_target(target) {}

    QString m_target;
};
