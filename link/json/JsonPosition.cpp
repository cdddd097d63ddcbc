#include "link/json/JsonPosition.h"

JsonLineColumn jsonLineColumn(const QByteArray& text, int offset)
{
    JsonLineColumn at;
    for (int i = 0; i < offset && i < text.size(); ++i) {
        if (text[i] == '\n') {
            ++at.line;
            at.column = 1;
        } else {
            ++at.column;
        }
    }
    return at;
}

QString jsonPosition(const QByteArray& text, int offset)
{
    const JsonLineColumn at = jsonLineColumn(text, offset);
    return QStringLiteral("line %1, column %2").arg(at.line).arg(at.column);
}
