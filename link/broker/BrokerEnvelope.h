#pragma once

// What every message a console publishes on a broker goes in: the report
// (BrokerTopics.h), who sends it, its number, and the station's signature
// over all of that and the topic. docs/security.md, "The broker", has the
// threat model; this header has the exact bytes.
//
// JSON, one object:
//   {"v":1, "station":"GB_30226", "seq":1764000000000001,
//    "body":"{...the report's JSON...}",                        unsealed, or
//    "sealed":"<base64: nonce, ciphertext, tag>", "key":"<16 hex>",   sealed
//    "will":true,            the station's will (absent: false)
//    "willSeq":1764000000000000,   station reports: the seq of the will set now
//    "sig":"<base64 of 64 bytes>"}  Ed25519; absent: unsigned
//
// seq: per station, strictly increasing over every topic and every run of
// the console: max(the last + 1, UTC microseconds now). A reader takes a
// station's messages on each topic only in increasing seq (SequenceCheck).
// sealed: a keyed session's report, AES-256-GCM under the key derived from
// the link's key (codec/secure/BrokerSeal.h), the topic as associated data;
// "key" is the link key's fingerprint, so a reader knows which key opens it.
//
// The signature is over these bytes (big-endian integers):
//   "RCM-GCS v1 broker message" 00
//   u32 length, topic (UTF-8)  u32 length, station (UTF-8)
//   i64 seq  u8 flags (1 sealed, 2 will)  i64 willSeq
//   u32 length, key fingerprint (ASCII, empty when not sealed)
//   the body: the report's JSON, or the sealed bytes
// so that no message can be moved to another topic, another station's name,
// another number, or turned into a will.

#include "link/broker/BrokerTopics.h"

#include <QByteArray>
#include <QMetaType>
#include <QString>

#include <optional>

struct BrokerEnvelope {
    static constexpr int kVersion = 1;

    QString station;
    qint64 seq = 0;
    bool will = false;
    qint64 willSeq = 0;  // 0: none said
    bool sealed = false;
    QString keyFingerprint;  // sealed only
    QByteArray body;         // the report's JSON, or (sealed) nonce || ciphertext || tag
    QByteArray signature;    // empty: unsigned

    QByteArray toJson() const;
    // Nothing, with what is wrong ("envelope: seq is missing"), for anything
    // but an envelope of this version.
    static std::optional<BrokerEnvelope> fromJson(const QByteArray& json, QString* error);
    // What the signature is over, as published on `topic`.
    QByteArray signedBytes(const QString& topic) const;

    friend bool operator==(const BrokerEnvelope&, const BrokerEnvelope&) = default;
};

// One message as a reader found it (BrokerTrust::open): whose, how far it
// can be trusted, and its report's JSON when it could be read.
struct OpenedMessage {
    enum class Trust : quint8 {
        Verified,    // signed by the key trusted for its station
        Unverified,  // its station has no trusted key: it may be anyone's
        Refused,     // forged, unsigned in a trusted station's name, malformed, too large, replayed
    };

    QString topic;
    std::optional<BrokerTopics::Topic> where;
    Trust trust = Trust::Refused;
    // Refused: "reason: detail", the reason one word or two ("forged",
    // "unsigned", "malformed", "too large", "replayed", "unreadable"), as
    // refused frames are told.
    QString refusal;
    bool retained = false;  // delivered as the topic's retained message
    bool cleared = false;   // an empty payload: a retained message removed

    QString station;  // the envelope's (the topic's)
    qint64 seq = 0;
    bool will = false;
    qint64 willSeq = 0;
    bool sealed = false;
    QString keyFingerprint;
    // Sealed and no key of ours opens it: the body is empty, and all there
    // is to know is that the station's session exists.
    bool opened = true;
    QByteArray body;  // the report's JSON, when unsealed or opened

    bool verified() const { return trust == Trust::Verified; }
    bool refused() const { return trust == Trust::Refused; }
    // Refuses it with "reason: detail".
    void refuse(const QString& reasonAndDetail)
    {
        trust = Trust::Refused;
        refusal = reasonAndDetail;
    }
};

Q_DECLARE_METATYPE(OpenedMessage)
