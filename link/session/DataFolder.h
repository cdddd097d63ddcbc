#pragma once

// The folder of the files that come with the programs: rehearsal scenarios,
// flight plans, airframes, samples. Installed, it is share/rcm-gcs beside the
// bin folder the program runs from (/usr/share/rcm-gcs for /usr/bin/gcs). A
// build tree has the same layout: build/share/rcm-gcs is a link to the
// sources' resources/ (cmake/Packaging.cmake), so one rule finds both, and a
// copy of the programs elsewhere finds the folder installed beside them.
#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>

class DataFolder {
public:
    // The folder, or a subfolder of it ("scenarios"); empty when there is none.
    static QString path(const QString& subfolder = {})
    {
        const QDir data(QCoreApplication::applicationDirPath() + QStringLiteral("/../share/rcm-gcs"));
        const QString folder = QDir::cleanPath(data.filePath(subfolder));
        return QFileInfo(folder).isDir() ? folder : QString();
    }
};
