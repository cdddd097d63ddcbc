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
