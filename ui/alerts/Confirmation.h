#pragma once

// The one way the console asks before an action that changes what the
// aircraft gets: a dialog whose default and Escape are Cancel and whose
// action button takes no focus, so a stray Enter, Space or Escape never
// confirms.

#include <QMessageBox>
#include <QString>

struct Confirmation {
    QMessageBox::Icon icon = QMessageBox::Warning;
    QString title;
    QString text;
    QString informativeText;
    QString action;  // the button that confirms: "Disconnect", "Upload"
    QMessageBox::ButtonRole role = QMessageBox::DestructiveRole;

    // True when the operator clicked the action button.
    bool ask(QWidget* parent) const;

    // `action` ("Quit", "Disconnect") would end the live link `link` (its
    // description; empty while one is being started).
    static Confirmation endingLink(const QString& title, const QString& action, const QString& link);
};
