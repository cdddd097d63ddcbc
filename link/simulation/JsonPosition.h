#pragma once

#include <QByteArray>
#include <QString>

// "line 3, column 7": where a byte offset (QJsonParseError::offset) falls in
// a JSON text, for error messages people can act on.
QString jsonPosition(const QByteArray& text, int offset);
