#include "ui/alerts/Confirmation.h"

#include <QPushButton>

bool Confirmation::ask(QWidget* parent) const
{
    QMessageBox box(icon, title, text, QMessageBox::NoButton, parent);
    if (!informativeText.isEmpty())
        box.setInformativeText(informativeText);
    QPushButton* go = box.addButton(action, role);
    go->setFocusPolicy(Qt::NoFocus);
    QPushButton* cancel = box.addButton(QMessageBox::Cancel);
    box.setDefaultButton(cancel);
    box.setEscapeButton(cancel);
    box.exec();
    return box.clickedButton() == go;
}

Confirmation Confirmation::endingLink(const QString& title, const QString& action, const QString& link)
{
    Confirmation ending;
    ending.title = title;
    ending.text = QObject::tr("%1 ends the live link: %2.")
                      .arg(action, link.isEmpty() ? QObject::tr("a link being started") : link);
    ending.informativeText = QObject::tr("The aircraft stops receiving this console's commands.");
    ending.action = action;
    return ending;
}
