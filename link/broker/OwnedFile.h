#pragma once

// The files whose contents the console takes on trust (the broker password,
// the stations whose keys it trusts) are read only when none but their owner
// may change them: anyone else could slip in a password or a key.

#include <QFile>
#include <QString>

#include <optional>

namespace OwnedFile {

// Opens `file` (its name set) for reading if it is a regular file whose
// permission bits have none of `forbidden` set. Otherwise the reason, which
// calls it "the <what> file <path>" and, for its mode, says what others than
// its owner could do (`risk`) and the chmod that mends it (`mendMode`, e.g. "600").
std::optional<QString> open(QFile& file, const QString& what, unsigned forbidden, const QString& risk,
                            const QString& mendMode);

}  // namespace OwnedFile
