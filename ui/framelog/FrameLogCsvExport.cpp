#include "ui/framelog/FrameLogCsvExport.h"

#include "codec/receive/LoggedFrameReading.h"
#include "link/framelog/FrameLogCsv.h"

#include <QSaveFile>
#include <QThread>

FrameLogCsvExport* FrameLogCsvExport::start(const QString& source, const QString& target,
                                            std::shared_ptr<const rcm::LogKey> key, QObject* parent)
{
    auto* job = new FrameLogCsvExport(target, parent);
    // The thread only touches `result`; this thread reads it once the thread has finished.
    struct Result {
        bool ok = false;
        QString error;
    };
    auto result = std::make_shared<Result>();
    auto* thread = QThread::create([source, target, result, key = std::move(key)] {
        QSaveFile out(target);
        result->ok =
            out.open(QIODevice::WriteOnly) && exportFrameLogCsv(source, out, &result->error, key.get()) && out.commit();
        if (!result->ok && result->error.isEmpty())
            result->error = out.errorString();
    });
    connect(thread, &QThread::finished, job, [job, result] {
        emit job->finished(result->ok, result->error);
        job->deleteLater();
    });
    connect(thread, &QThread::finished, thread, &QObject::deleteLater);
    thread->start();
    return job;
}
