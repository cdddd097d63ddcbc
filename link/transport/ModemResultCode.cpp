#include "link/transport/ModemResultCode.h"

#include <QList>

#include <array>
#include <utility>

namespace modem {

namespace {

constexpr std::array<std::pair<ResultCode, const char*>, 8> kTexts{{
    {ResultCode::Ok, "OK"},
    {ResultCode::Connect, "CONNECT"},
    {ResultCode::Ring, "RING"},
    {ResultCode::NoCarrier, "NO CARRIER"},
    {ResultCode::Error, "ERROR"},
    {ResultCode::NoDialtone, "NO DIALTONE"},
    {ResultCode::Busy, "BUSY"},
    {ResultCode::NoAnswer, "NO ANSWER"},
}};

}  // namespace

std::optional<Result> parseResult(QByteArrayView line)
{
    // Liberal: either case, spaces anywhere between the words.
    const QByteArray text = line.toByteArray().simplified().toUpper();
    for (const auto& [code, name] : kTexts) {
        if (text == name)
            return Result{code, 0};
    }
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
    for (const auto& [code, name] : kTexts) {
        if (code == result.code) {
            QByteArray text(name);
            if (result.code == ResultCode::Connect && result.rate > 0)
                text += ' ' + QByteArray::number(result.rate);
            return text;
        }
    }
    return {};
}

QByteArray resultLine(Result result)
{
    return "\r\n" + resultText(result) + "\r\n";
}

}  // namespace modem
