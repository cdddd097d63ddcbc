// A panel of repeated units (engines, radios, cameras): one card per unit of
// the airframe, two to a row (CardGrid), made again whenever CommandState's
// airframe changes.
#pragma once

#include "codec/message/ItemTable.h"
#include "ui/panels/UnitRef.h"

#include <QWidget>

#include <vector>

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
    // A card for each unit of `kind` the airframe lists in `specs` (its
    // engines, its radios ...), titled `title(spec)`, its key the first row,
    // then the rows `fill(card)` adds; placed.
    template <typename Spec, typename Title, typename Fill>
    void addUnitCards(rcm::UnitKind kind, const std::vector<Spec>& specs, Title title, Fill fill)
    {
        for (std::size_t i = 0; i < specs.size(); ++i) {
            UnitCard* card = newUnitCard({kind, static_cast<int>(i)}, title(specs[i]));
            fill(card);
            place(card);
        }
    }
    // A card with this panel as parent and the unit's key as its first row.
    UnitCard* newUnitCard(UnitRef ref, const QString& title);

    CommandState* m_command;
    ReportedState* m_reported;

private:
    QGridLayout* m_layout;
};
