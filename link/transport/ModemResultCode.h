#pragma once

// Hayes/V.250 result codes in their verbose form (V1), as a modem says them
// and as the satellite modem model (link/satmodem/SatelliteModem) says them
// to its callers: "\r\n" TEXT "\r\n". One list for both sides, so that what
// the console listens for is what the model sends.

#include <QByteArray>
#include <QByteArrayView>

#include <optional>

namespace modem {

enum class ResultCode { Ok, Connect, Ring, NoCarrier, Error, NoDialtone, Busy, NoAnswer };

struct Result {
    ResultCode code = ResultCode::Ok;
    int rate = 0;  // "CONNECT 9600": 9600; 0 when the modem gave none

    friend bool operator==(const Result&, const Result&) = default;
};

// One line as the modem sent it, without its CR/LF: "CONNECT 9600",
// "NO CARRIER". Nothing for an echoed command, an empty line or any other text.
std::optional<Result> parseResult(QByteArrayView line);

// The text of a result code, "CONNECT 9600" for {Connect, 9600}.
QByteArray resultText(Result result);
// As a modem sends it: "\r\nCONNECT 9600\r\n".
QByteArray resultLine(Result result);

// The escape from data to command mode: this, with a guard time of silence
// before and after it (S12, 1 s by default).
inline constexpr char kEscapeSequence[] = "+++";

}  // namespace modem
