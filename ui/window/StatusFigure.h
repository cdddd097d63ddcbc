#pragma once

// One of the status bar's figures: a name in grey and a value in bold, side
// by side ("Received 1,234"). Both are plain text in labels of their own: the
// value changes with every frame, and a rich-text label parses and lays out a
// document for each new text (a third of a millisecond of the GUI thread, at
// 10x replay twenty times a second per figure). The value keeps its room as
// it changes (a SteadyLabel), so a new count repaints the value alone.

#include <QColor>
#include <QWidget>

class QLabel;
class SteadyLabel;

class StatusFigure : public QWidget {
    Q_OBJECT

public:
    StatusFigure(const QString& name, const QString& toolTip, QWidget* parent = nullptr);

    void setName(const QString& name);
    void setValue(const QString& value);
    // The value's colour; an invalid colour: the window's text colour.
    void setValueColour(const QColor& colour);

    // "Received 1,234", as read.
    QString text() const;
    QString value() const;

private:
    QLabel* m_name;
    SteadyLabel* m_value;
    QColor m_colour;
};
