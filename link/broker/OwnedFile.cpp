#include "link/broker/OwnedFile.h"

#include <sys/stat.h>

namespace OwnedFile {

std::optional<QString> open(QFile& file, const QString& what, unsigned forbidden, const QString& risk,
                            const QString& mendMode)
{
    const QString path = file.fileName();
    if (!file.open(QIODevice::ReadOnly))
        return QStringLiteral("cannot open the %1 file %2: %3").arg(what, path, file.errorString());
    // Judged on the open file, so the file judged is the file read.
    struct stat st {};
    if (::fstat(file.handle(), &st) != 0 || !S_ISREG(st.st_mode))
        return QStringLiteral("the %1 file %2 is not a regular file").arg(what, path);
    if (st.st_mode & forbidden)
        return QStringLiteral(
                   "the %1 file %2 has mode %3: others than its owner %4, so it is refused; run: chmod %5 %2")
            .arg(what, path, QStringLiteral("%1").arg(uint(st.st_mode & 07777), 4, 8, QLatin1Char('0')), risk,
                 mendMode);
    return std::nullopt;
}

}  // namespace OwnedFile
