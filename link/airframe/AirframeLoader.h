#pragma once

// Airframes as JSON files, the format `uasim --airframe` reads too:
//
//     {
//         "name": "Well-equipped UA",
//         "engines": [{"id": 1, "name": "Engine 1"}, ...],          id 0..255, each once
//         "radios": [{"systemId": "VHF1", "name": "VHF 1"}, ...],   1..8 printable ASCII, each once
//         "cameras": [{"maker": "NIK", "number": 1, "name": "..."}], 3 printable ASCII + 0..255
//         "senseAndAvoid": true
//     }
//
// Every member but "name" may be left out (no units of that kind; sense and
// avoid fitted). A file that says anything else (an unknown member, a wrong
// type, a duplicate unit, units whose resting command does not fit in BLOCK 1)
// is refused with one message naming the file and the fault, so a typo never
// silently removes an engine. The built-in airframes are Qt resources under
// :/airframes/; the default is Airframe::wellEquipped() as a file.

#include "codec/message/Airframe.h"

#include <QByteArray>
#include <QString>
#include <QStringList>

#include <optional>

class AirframeLoader {
public:
    static const QString kDefaultPath;  // ":/airframes/well-equipped.json"

    // Reads and checks a file (a resource path works); nothing, with the
    // reason in `error`, when it cannot be used.
    static std::optional<rcm::Airframe> load(const QString& path, QString* error = nullptr);
    // `source` names the JSON in error messages.
    static std::optional<rcm::Airframe> fromJson(const QByteArray& json, const QString& source,
                                                 QString* error = nullptr);
    // The inverse of fromJson, for handing an airframe to uasim.
    static QByteArray toJson(const rcm::Airframe& airframe);

    // The resource paths of the built-in airframes, sorted.
    static QStringList builtIn();
};
