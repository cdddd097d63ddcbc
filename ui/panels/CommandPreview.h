#pragma once

// The next frame before it goes: the command in the text format and the
// bytes the link will send, with what changed since the last frame sent
// marked, so that the operator sees exactly what a click will do to the
// aircraft one second later. The bytes are those the link's send path
// (codec/send/FrameBuilder.h) builds: ID_msg is the one after the last frame
// sent, time_UTC and date_UTC those of the link's next tick on the link's
// clock, enciphered when the link is keyed. They change every frame and are
// not marked.

#include "codec/message/Message.h"

#include <QTabWidget>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>

namespace rcm::secure {
class SecureCodec;
}

class QLabel;
class QTextEdit;

class CommandPreview : public QWidget {
    Q_OBJECT

public:
    explicit CommandPreview(QWidget* parent = nullptr);

    // Serial frames carry the 90-byte preamble; UDP datagrams do not.
    void setDatagram(bool datagram);
    // The keyed link's codec for what the console sends (GCS->UA); null for
    // the plain link.
    void setCipher(std::shared_ptr<const rcm::secure::SecureCodec> cipher);
    // The UTC clock (microseconds) the link stamps its frames on, and its
    // interval; unset, the system clock at 1 s, as a LinkWorker by default.
    void setClock(std::function<std::int64_t()> utcMicros,
                  std::chrono::milliseconds interval = std::chrono::milliseconds(1000));
    // Items of the next frame that differ from the last frame sent; 0 before any.
    int changedItems() const;
    QString text() const;  // plain, without marks
    QString hex() const;
    // The bytes of the next frame as the link will send them; empty when the
    // command cannot be encoded.
    QByteArray bytes() const;
    // Not a slot: rcm::Message's meta type is declared in link/session/MessageMetaType.h,
    // which this widget has no need of.
    void setCommand(const rcm::Message& command);

public slots:
    // The command as it stands went out as frame `messageId`.
    void frameSent(quint32 messageId);
    // A new link: nothing has been sent on it yet; its first frame will be `firstMessageId`.
    void resetSent(quint32 firstMessageId = 0);

protected:
    // A new theme: the muted colour of the text view follows it.
    void changeEvent(QEvent* event) override;
    void showEvent(QShowEvent* event) override;

private:
    // One line of the items view, as shown.
    enum class LineKind { Item, ChangedItem, Section };
    struct PreviewLine {
        QString text;
        LineKind kind;
        bool operator==(const PreviewLine&) const = default;
    };

    // Changes are shown once per pass of the event loop, and only while the
    // preview is visible (the hex dump only while its tab is): at 10x replay
    // the command and the next ID change ten times a second, and each
    // showing sets two rich-text views, milliseconds of the GUI thread.
    void invalidate();
    void refresh();
    void refreshHex();
    // Rewrites only the lines that differ from those shown (a frame changes
    // the ID, the time and what is marked: a few of some hundred lines), so
    // that the view lays out those lines alone; all of them when the lines
    // are others.
    void showLines(const QList<PreviewLine>& lines);
    // For the accessors: what they read is up to date whether shown or not.
    void ensureFresh() const;

    rcm::Message m_command;
    std::optional<rcm::Message> m_lastSent;
    quint32 m_nextId = 0;
    bool m_datagram = true;
    std::shared_ptr<const rcm::secure::SecureCodec> m_cipher;
    std::function<std::int64_t()> m_utcMicros;  // empty: the system clock
    std::chrono::milliseconds m_interval{1000};
    int m_changedItems = 0;
    bool m_stale = true;
    bool m_refreshQueued = false;
    bool m_hexStale = true;
    QByteArray m_bytes;          // the next frame; empty when it cannot be encoded
    QByteArray m_previousBytes;  // the last frame sent, stamped as the next
    QString m_encodeErrors;      // why the next frame cannot be encoded, as HTML list items
    QList<PreviewLine> m_shownLines;
    QLabel* m_summary;
    QTabWidget* m_tabs;
    QTextEdit* m_text;
    QTextEdit* m_hex;
};
