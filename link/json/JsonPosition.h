#pragma once

#include <QByteArray>
#include <QString>

// Where a byte offset (QJsonParseError::offset) falls in a JSON text, both
// counted from 1, for error messages people can act on.
struct JsonLineColumn {
    int line = 1;
    int column = 1;
};
JsonLineColumn jsonLineColumn(const QByteArray& text, int offset);

// "line 3, column 7": the same in words.
QString jsonPosition(const QByteArray& text, int offset);
