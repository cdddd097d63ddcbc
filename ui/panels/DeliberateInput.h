// What every control that edits the command shares: it changes the command
// only by deliberate input. A mouse wheel turned over a panel to scroll it is
// not deliberate, so a command control never reacts to the wheel, lets the
// surrounding area scroll instead, and does not take the focus from it
// (Qt::StrongFocus: Tab and clicks, never the wheel).
#pragma once

#include <QString>

class QWidget;

namespace DeliberateInput {

// Applies the above to `control` (keeps Qt::NoFocus if the control has it).
void protect(QWidget* control);

// Marks for what an operator has typed and is not (yet) commanded, as a
// style sheet for widgets of `className` ("QLineEdit"): "edited", complete
// but not sent yet (pale blue); "invalid", not a value the item takes or
// incomplete (amber). Dark text on a light background in day and night themes.
QString editedStyle(const char* className);
QString invalidStyle(const char* className);

}  // namespace DeliberateInput
