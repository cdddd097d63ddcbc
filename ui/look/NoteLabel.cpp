#include "ui/look/NoteLabel.h"

#include <QEvent>
#include <QFontMetrics>
#include <QTextLayout>

NoteLabel::NoteLabel(int lines, QWidget* parent) : QLabel(parent), m_lines(std::max(1, lines))
{
    setTextFormat(Qt::RichText);
    setWordWrap(true);
    setAlignment(Qt::AlignLeft | Qt::AlignVCenter);
    // Its width is what the layout gives it, never what the text asks for;
    // its height the room of `lines` lines, whatever the text.
    setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
    setMinimumWidth(0);
    QFont bold = font();
    bold.setBold(true);
    setFixedHeight(QFontMetrics(bold).lineSpacing() * m_lines + 2 * margin() + 2);
}

void NoteLabel::setNote(const QString& text, std::optional<SeverityColours::Severity> severity)
{
    if (text == m_note && severity == m_severity)
        return;
    m_note = text;
    m_severity = severity;
    render();
}

void NoteLabel::resizeEvent(QResizeEvent* event)
{
    QLabel::resizeEvent(event);
    render();
}

void NoteLabel::changeEvent(QEvent* event)
{
    QLabel::changeEvent(event);
    if (event->type() == QEvent::PaletteChange || event->type() == QEvent::FontChange)
        render();
}

void NoteLabel::render()
{
    if (m_rendering)
        return;
    m_rendering = true;
    QFont shownFont = font();
    shownFont.setBold(m_severity.has_value());
    const QFontMetrics metrics(shownFont);
    // The room of bold lines whatever the note: a note that turns into an error keeps the room.
    QFont bold = font();
    bold.setBold(true);
    setFixedHeight(std::max(QFontMetrics(bold).lineSpacing(), metrics.lineSpacing()) * m_lines + 2 * margin() + 2);
    // The words that fit `m_lines` lines of the width as the label wraps
    // them, the last line cut with an ellipsis when more would follow.
    const int width = std::max(1, contentsRect().width() - 2 * margin());
    QString shown = m_note;
    QTextLayout layout(m_note, shownFont);
    layout.beginLayout();
    int lines = 0;
    for (QTextLine line = layout.createLine(); line.isValid(); line = layout.createLine()) {
        line.setLineWidth(width);
        if (++lines == m_lines) {
            const QString rest = m_note.mid(line.textStart());
            const QString last = metrics.elidedText(rest, Qt::ElideRight, width);
            if (last != rest)
                shown = m_note.left(line.textStart()) + last;
            break;
        }
    }
    layout.endLayout();
    m_cut = shown != m_note;
    setToolTip(m_cut ? m_note : QString());
    setText(m_severity ? SeverityColours::span(*m_severity, palette(), shown) : shown.toHtmlEscaped());
    m_rendering = false;
}
