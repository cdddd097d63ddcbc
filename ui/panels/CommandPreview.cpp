#include "ui/panels/CommandPreview.h"

#include "codec/message/TextFormat.h"
#include "codec/send/FrameBuilder.h"
#include "ui/framelog/HexDump.h"

#include <QEvent>
#include <QFontDatabase>
#include <QHash>
#include <QLabel>
#include <QTextBlock>
#include <QTextCursor>
#include <QTextDocument>
#include <QTextEdit>
#include <QVBoxLayout>

namespace {

// Each line of a message's text with a key naming the item it sets: the
// sections it is in, the key item line of its unit, and the item's name. Two
// texts' lines with one key are the same item of the same unit.
struct KeyedLine {
    QString key;  // empty for section lines
    QString line;
};

QList<KeyedLine> keyedLines(const std::string& text)
{
    static const QStringList repeated = {QStringLiteral("engine"), QStringLiteral("comms_system"),
                                         QStringLiteral("camera")};
    QList<KeyedLine> out;
    QStringList sections;
    QString unit;  // the key item line of the repeated unit being read
    for (const QString& line : QString::fromStdString(text).split(QLatin1Char('\n'), Qt::SkipEmptyParts)) {
        if (line.startsWith(QLatin1String("BEGIN "))) {
            sections << line.mid(6);
            unit.clear();
            out.append({QString(), line});
        } else if (line == QLatin1String("END")) {
            if (!sections.isEmpty())
                sections.removeLast();
            unit.clear();
            out.append({QString(), line});
        } else {
            // In canonical order a repeated unit's key item is its first line.
            if (!sections.isEmpty() && repeated.contains(sections.last()) && unit.isEmpty())
                unit = line;
            const QString name = line.section(QLatin1Char(' '), 0, 0);
            out.append({sections.join(QLatin1Char('/')) + QLatin1Char('|') + unit + QLatin1Char('|') + name, line});
        }
    }
    return out;
}

QTextEdit* codeView()
{
    auto* view = new QTextEdit;
    view->setReadOnly(true);
    view->setLineWrapMode(QTextEdit::NoWrap);
    view->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
    view->setUndoRedoEnabled(false);  // nothing to undo in a read-only view, and each change would be kept
    return view;
}

// Dark on pale yellow whatever the theme's text colour.
const QString kMarkStyle = QStringLiteral("background-color:#ffe08a; color:black");
const QColor kMarkBackground(0xff, 0xe0, 0x8a);

// Lines that are not items (section names): the theme's text colour a third
// of the way to its background, readable in day and night themes alike.
QString mutedColour(const QPalette& palette)
{
    const QColor text = palette.color(QPalette::Text);
    const QColor base = palette.color(QPalette::Base);
    auto mix = [](int a, int b) { return (2 * a + b) / 3; };
    return QColor(mix(text.red(), base.red()), mix(text.green(), base.green()), mix(text.blue(), base.blue())).name();
}

QTextCharFormat changedFormat()
{
    QTextCharFormat format;
    format.setBackground(kMarkBackground);
    format.setForeground(QColor(Qt::black));
    format.setFontWeight(QFont::Bold);
    return format;
}

}  // namespace

CommandPreview::CommandPreview(QWidget* parent)
    : QWidget(parent), m_summary(new QLabel), m_tabs(new QTabWidget), m_text(codeView()), m_hex(codeView())
{
    m_summary->setWordWrap(true);
    m_text->setObjectName(QStringLiteral("previewItems"));
    m_hex->setObjectName(QStringLiteral("previewBytes"));
    m_tabs->addTab(m_text, tr("Items"));
    m_tabs->addTab(m_hex, tr("Bytes"));
    m_tabs->setDocumentMode(true);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(6, 6, 6, 6);
    layout->addWidget(m_summary);
    layout->addWidget(m_tabs, 1);
    connect(m_tabs, &QTabWidget::currentChanged, this, [this] {
        if (m_hexStale && m_tabs->currentWidget() == m_hex)
            refreshHex();
    });
    refresh();
}

void CommandPreview::setDatagram(bool datagram)
{
    if (datagram == m_datagram)
        return;
    m_datagram = datagram;
    invalidate();
}

void CommandPreview::setCipher(std::shared_ptr<const rcm::secure::SecureCodec> cipher)
{
    if (cipher == m_cipher)
        return;
    m_cipher = std::move(cipher);
    invalidate();
}

void CommandPreview::setClock(std::function<std::int64_t()> utcMicros, std::chrono::milliseconds interval)
{
    m_utcMicros = std::move(utcMicros);
    m_interval = interval;
    invalidate();
}

QString CommandPreview::text() const
{
    ensureFresh();
    return m_text->toPlainText();
}

QString CommandPreview::hex() const
{
    ensureFresh();
    if (m_hexStale)
        const_cast<CommandPreview*>(this)->refreshHex();
    return m_hex->toPlainText();
}

QByteArray CommandPreview::bytes() const
{
    ensureFresh();
    return m_bytes;
}

int CommandPreview::changedItems() const
{
    ensureFresh();
    return m_changedItems;
}

void CommandPreview::ensureFresh() const
{
    if (m_stale)
        const_cast<CommandPreview*>(this)->refresh();
}

void CommandPreview::invalidate()
{
    m_stale = true;
    if (m_refreshQueued)
        return;
    m_refreshQueued = true;
    QMetaObject::invokeMethod(
        this,
        [this] {
            m_refreshQueued = false;
            if (m_stale && isVisible())
                refresh();
        },
        Qt::QueuedConnection);
}

void CommandPreview::showEvent(QShowEvent* event)
{
    QWidget::showEvent(event);
    ensureFresh();
}

void CommandPreview::setCommand(const rcm::Message& command)
{
    m_command = command;
    invalidate();
}

void CommandPreview::frameSent(quint32 messageId)
{
    m_lastSent = m_command;
    m_nextId = (messageId + 1) % rcm::kMessageIdModulus;
    invalidate();
}

void CommandPreview::changeEvent(QEvent* event)
{
    QWidget::changeEvent(event);
    if (event->type() == QEvent::PaletteChange) {
        m_shownLines.clear();  // the section lines' colour follows the theme
        invalidate();
    }
}

void CommandPreview::resetSent(quint32 firstMessageId)
{
    m_lastSent.reset();
    m_nextId = firstMessageId % rcm::kMessageIdModulus;
    invalidate();
}

void CommandPreview::refresh()
{
    m_stale = false;
    // Stamped as the link will stamp the next frame.
    const std::int64_t now =
        m_utcMicros
            ? m_utcMicros()
            : std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
                  .count();
    const rcm::SendStamp stamp{m_nextId, rcm::nextSendMicros(now, m_interval)};
    const rcm::SendFormat format{m_datagram, m_cipher.get()};
    rcm::Message next = m_command;
    rcm::stampMessage(next, stamp);
    std::optional<rcm::Message> before = m_lastSent;
    if (before)
        rcm::stampMessage(*before, stamp);  // the same stamp, so only the command's changes differ

    // Items.
    QHash<QString, QString> previous;
    if (before)
        for (const KeyedLine& k : keyedLines(rcm::formatMessage(*before)))
            if (!k.key.isEmpty())
                previous.insert(k.key, k.line);
    QList<PreviewLine> lines;
    m_changedItems = 0;
    for (const KeyedLine& k : keyedLines(rcm::formatMessage(next))) {
        const bool changed = before && !k.key.isEmpty() && previous.value(k.key) != k.line;
        m_changedItems += changed;
        lines.append({k.line, changed ? LineKind::ChangedItem : k.key.isEmpty() ? LineKind::Section : LineKind::Item});
    }
    showLines(lines);

    // Bytes.
    rcm::Diagnostics errors;
    const auto encode = [&](const rcm::Message& m, rcm::Diagnostics& e) -> QByteArray {
        const std::vector<std::uint8_t> bytes = rcm::buildFrame(m, format, e);
        return QByteArray(reinterpret_cast<const char*>(bytes.data()), qsizetype(bytes.size()));
    };
    m_bytes = encode(next, errors);
    m_encodeErrors.clear();
    for (const rcm::Diagnostic& d : errors)
        m_encodeErrors += QStringLiteral("<li>%1</li>").arg(QString::fromStdString(d.toString()).toHtmlEscaped());
    rcm::Diagnostics ignored;
    m_previousBytes = before && !m_bytes.isEmpty() ? encode(*before, ignored) : QByteArray();
    m_hexStale = true;
    if (m_tabs->currentWidget() == m_hex)
        refreshHex();
    if (m_bytes.isEmpty()) {
        m_summary->setText(QStringLiteral("<span style=\"color:#b01c1c\">%1</span>").arg(tr("Not encodable")));
        return;
    }
    const QByteArray& bytes = m_bytes;

    const QString framing =
        m_datagram ? tr("%1-byte UDP datagram").arg(bytes.size()) : tr("%1-byte serial frame").arg(bytes.size());
    // Not the next ID (the items show it): a wrapped label asks the window's
    // layouts for room again on every new text, and the ID is new in every
    // frame, ten times a second at 10x.
    if (!before)
        m_summary->setText(tr("Next frame: %1. No frame sent yet.").arg(framing));
    else if (m_changedItems == 0)
        m_summary->setText(tr("Next frame: %1. Same command as the last frame sent.").arg(framing));
    else
        m_summary->setText(
            tr("Next frame: %1. <span style=\"%2\"><b>%3</b></span> since the last frame sent.")
                .arg(framing, kMarkStyle,
                     m_changedItems == 1 ? tr("1 item changed") : tr("%1 items changed").arg(m_changedItems)));
}

void CommandPreview::showLines(const QList<PreviewLine>& lines)
{
    QTextCharFormat section;
    section.setForeground(QColor(mutedColour(m_text->palette())));
    const QTextCharFormat changed = changedFormat();
    const auto format = [&](LineKind kind) {
        return kind == LineKind::ChangedItem ? changed : kind == LineKind::Section ? section : QTextCharFormat();
    };
    QTextDocument* document = m_text->document();
    const bool anew = lines.size() != m_shownLines.size() || document->blockCount() != lines.size();
    if (anew)
        document->clear();
    QTextCursor cursor(document);
    cursor.beginEditBlock();
    if (anew) {
        for (qsizetype i = 0; i < lines.size(); ++i) {
            if (i > 0)
                cursor.insertBlock();
            cursor.insertText(lines[i].text, format(lines[i].kind));
        }
    } else {
        QTextBlock block = document->begin();
        for (qsizetype i = 0; i < lines.size(); ++i, block = block.next()) {
            if (lines[i] == m_shownLines[i])
                continue;
            cursor.setPosition(block.position());
            cursor.setPosition(block.position() + block.length() - 1, QTextCursor::KeepAnchor);
            cursor.insertText(lines[i].text, format(lines[i].kind));
        }
    }
    cursor.endEditBlock();
    m_shownLines = lines;
}

void CommandPreview::refreshHex()
{
    m_hexStale = false;
    if (m_bytes.isEmpty()) {
        m_hex->setHtml(
            QStringLiteral("<p style=\"color:#b01c1c\"><b>%1</b></p><ul>%2</ul>")
                .arg(tr("This command cannot be encoded; the link keeps sending the last good one."), m_encodeErrors));
        return;
    }
    QList<bool> marked(m_bytes.size(), false);
    if (m_previousBytes.size() == m_bytes.size())
        for (const HexDumpPart& part : frameParts(m_bytes.size()))
            if (part.title.endsWith(QLatin1String("data")))  // parity changes with any data byte
                for (qsizetype i = part.offset; i < part.offset + part.length; ++i)
                    marked[i] = m_bytes[i] != m_previousBytes[i];
    m_hex->setHtml(
        QStringLiteral("<pre style=\"margin:0\">%1</pre>").arg(hexDump(m_bytes, frameParts(m_bytes.size()), &marked)));
}
