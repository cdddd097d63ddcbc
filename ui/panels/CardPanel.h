// A panel of repeated units (engines, radios, cameras): one card per unit of
// the airframe, two to a row (CardGrid), made again whenever CommandState's
// airframe changes.
#pragma once

#include <QWidget>

class CommandState;
class QGridLayout;
class ReportedState;
class UnitCard;

class CardPanel : public QWidget {
    Q_OBJECT

protected:
    CardPanel(CommandState* command, ReportedState* reported, const QString& objectName, QWidget* parent);

    // The cards of the airframe as it is now, the old ones gone. A derived
    // panel calls it at the end of its constructor (the base's cannot: the
    // derived part does not exist yet), CommandState whenever the airframe changes.
    void rebuild();
    // Makes each card (with this panel as parent) and places it.
    virtual void addCards() = 0;
    void place(UnitCard* card);

    CommandState* m_command;
    ReportedState* m_reported;

private:
    QGridLayout* m_layout;
};
