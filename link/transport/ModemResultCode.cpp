#include "link/transport/ModemResultCode.h"

#include "link/common/NameTable.h"

#include <QList>

namespace modem {

namespace {

using enum ResultCode;

constexpr auto kTexts = std::to_array<Named<ResultCode>>({
    {Ok, "OK"},
    {Connect, "CONNECT"},
    {Ring, "RING"},
    {NoCarrier, "NO CARRIER"},
    {Error, "ERROR"},
    {NoDialtone, "NO DIALTONE"},
    {Busy, "BUSY"},
    {NoAnswer, "NO ANSWER"},
});

}  // namespace

std::optional<Result> parseResult(QByteArrayView line)
{
    // Liberal: either case, spaces anywhere between the words.
    const QByteArray text = line.toByteArray().simplified().toUpper();
    if (const std::optional<ResultCode> code = valueIn(kTexts, text))
        return Result{*code, 0};
    // "CONNECT 9600", "CONNECT 9600/ARQ" (some modems add the protocol)
    if (text.startsWith("CONNECT ")) {
        bool ok = false;
        QByteArray digits = text.mid(8);
        digits.truncate(digits.indexOf('/') < 0 ? digits.size() : digits.indexOf('/'));
        const int rate = digits.toInt(&ok);
        if (ok && rate > 0)
            return Result{ResultCode::Connect, rate};
    }
    return std::nullopt;
}

QByteArray resultText(Result result)
{
    QByteArray text(nameOf(kTexts, result.code));
    if (result.code == ResultCode::Connect && result.rate > 0)
        text += ' ' + QByteArray::number(result.rate);
    return text;
}

QByteArray resultLine(Result result)
{
    return "\r\n" + resultText(result) + "\r\n";
}

}  // namespace modem
