// Answers the next modal confirmation (ui/alerts/Confirmation.h) as an
// operator would, and notes what it showed: its text, and whether Cancel was
// the default and held the focus, so that a stray Enter or Space cancels.
#pragma once

#include <QAbstractButton>
#include <QApplication>
#include <QMessageBox>
#include <QPushButton>
#include <QTimer>

namespace rcm::test {

struct SeenBox {
    bool shown = false;
    bool cancelIsDefault = false;
    bool cancelHasFocus = false;
    QString text;
    QString informativeText;
    QString actionText;  // the button that confirms
};

// Once the box is up (the next pass of the event loop), presses Cancel when
// `cancel`, else the action button.
inline void answerNextBox(SeenBox* seen, bool cancel)
{
    QTimer::singleShot(0, [seen, cancel] {
        auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
        if (!box)
            return;
        seen->shown = true;
        seen->text = box->text();
        seen->informativeText = box->informativeText();
        QAbstractButton* cancelButton = box->button(QMessageBox::Cancel);
        seen->cancelIsDefault = box->defaultButton() == cancelButton;
        seen->cancelHasFocus = box->focusWidget() == cancelButton;
        QAbstractButton* go = nullptr;
        for (QAbstractButton* b : box->buttons())
            if (b != cancelButton)
                go = b;
        seen->actionText = go ? go->text() : QString();
        (cancel ? cancelButton : go)->click();
    });
}

}  // namespace rcm::test
