// Airframe descriptions as JSON files (resources/airframes/*.json): the one
// reader that the console and the simulated aircraft share.
//
//   { "name": "Well-equipped UA", "senseAndAvoid": true,
//     "engines": [ { "id": 1, "name": "Engine 1" }, ... ],
//     "radios":  [ { "systemId": "VHF1", "name": "VHF 1" }, ... ],
//     "cameras": [ { "maker": "NIK", "number": 1, "name": "Payload camera 1" }, ... ] }
#pragma once

#include "codec/Airframe.h"

#include <QByteArray>
#include <QString>

#include <optional>

// Parses `json`; on failure returns nothing and says what is wrong in `error`
// (prefixed with `source`, e.g. the file name).
std::optional<rcm::Airframe> parseAirframe(const QByteArray& json, const QString& source, QString* error);

// Reads and parses a file (a path or a Qt resource path).
std::optional<rcm::Airframe> loadAirframe(const QString& path, QString* error);

// The JSON for an airframe: what parseAirframe reads back.
QByteArray airframeToJson(const rcm::Airframe& airframe);
