// A line of news for the operator (a refused plan, an acknowledgement, a
// fence warning) in a fixed room of a few lines: the text wraps, and what
// does not fit the room is cut with an ellipsis and shown whole in the tool
// tip, so a long message never pushes the widgets around it (the plan's map)
// out of their room. An error, a warning or a success is bold in its
// severity's colour for the palette it is shown in (SeverityColours), drawn
// again when the theme changes.
#pragma once

#include "ui/look/SeverityColours.h"

#include <QLabel>

#include <optional>

class NoteLabel : public QLabel {
    Q_OBJECT

public:
    explicit NoteLabel(int lines, QWidget* parent = nullptr);

    // Plain text; no severity: the palette's own text colour, normal weight.
    void setNote(const QString& text, std::optional<SeverityColours::Severity> severity = std::nullopt);
    void clearNote() { setNote({}); }
    QString note() const { return m_note; }
    std::optional<SeverityColours::Severity> severity() const { return m_severity; }
    // True when the room cut the note (its whole text is the tool tip).
    bool isCut() const { return m_cut; }

protected:
    void resizeEvent(QResizeEvent* event) override;
    void changeEvent(QEvent* event) override;

private:
    void render();

    int m_lines;
    QString m_note;
    std::optional<SeverityColours::Severity> m_severity;
    bool m_cut = false;
    bool m_rendering = false;
};
