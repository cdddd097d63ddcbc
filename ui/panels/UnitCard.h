// One unit of the command on screen (an engine, a radio, the flaps ...): a
// group box of rows "label | control | reported value", each label and
// control taken from the item table and bound to CommandState, each reported
// value a ReportedLabel bound to ReportedState. The glue every panel needs,
// written once. Its object name is the unit's ("engine 2", "radio VHF1").
#pragma once

#include "codec/message/ItemTable.h"
#include "ui/panels/SteadyGroupBox.h"
#include "ui/panels/UnitRef.h"

class CommandState;
class FieldButtonGroup;
class FieldComboBox;
class ItemSpinBox;
class QGridLayout;
class ReportedLabel;
class ReportedState;
class StationEditor;

class UnitCard : public SteadyGroupBox {
    Q_OBJECT

public:
    UnitCard(CommandState* command, ReportedState* reported, UnitRef ref, const QString& title,
             QWidget* parent = nullptr);

    // A card titled with the item's label and a button group for each of its
    // fields (the landing gear's four wheels, the lights).
    static UnitCard* ofFields(CommandState* command, ReportedState* reported, UnitRef ref, rcm::ItemId id,
                              QWidget* parent);

    UnitRef unitRef() const { return m_ref; }

    ItemSpinBox* addSpinBox(rcm::ItemId id);
    FieldComboBox* addComboBox(rcm::ItemId id, int field);
    FieldButtonGroup* addButtons(rcm::ItemId id, int field);
    StationEditor* addStation(rcm::ItemId id);
    // The unit's key, read-only: it names the unit and comes from the airframe.
    void addKey();
    // Any control for the item (or one field of it), with the item's label and
    // its reported value beside it.
    ReportedLabel* addRow(QWidget* control, rcm::ItemId id, int field = -1);

private:
    CommandState* m_command;
    ReportedState* m_reported;
    UnitRef m_ref;
    QGridLayout* m_grid;
    int m_rows = 0;
};
