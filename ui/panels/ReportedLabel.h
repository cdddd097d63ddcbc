// The value the aircraft last reported for one item (or one two-bit field of
// it), shown beside the control that commands it. When the report has
// disagreed with the command for more than two status frames the label is
// highlighted: property "mismatch" true, a warning background, and a tool tip
// saying what was commanded and what is reported. While no status frame
// comes (ReportedState::stale()) the value carries its age, "77 (stale, 12 s)",
// in italics in a dashed frame (property "stale"), and a command that differs
// from it shows as a mismatch at once.
#pragma once

#include "codec/message/ItemTable.h"
#include "codec/message/Message.h"
#include "ui/panels/SteadyLabel.h"
#include "ui/panels/UnitRef.h"

#include <optional>

class CommandState;
class ReportedState;

class ReportedLabel : public SteadyLabel {
    Q_OBJECT

public:
    ReportedLabel(const CommandState* command, const ReportedState* reported, UnitRef ref, rcm::ItemId id,
                  int field = -1, QWidget* parent = nullptr);

    bool mismatch() const { return property("mismatch").toBool(); }
    bool stale() const { return property("stale").toBool(); }
    // Where room is short (the overview's cards): a stale value is marked by
    // its look alone and its age is in the tool tip, "77" rather than
    // "77 (stale, 12 s)", so that the label keeps the width of its values.
    void setAgeShown(bool shown);

private:
    void refresh();
    // A value as shown: the item's, or its field's; "—" for none.
    QString valueText(const rcm::Value* value) const;

    // What the label shows was made from these; a refresh that finds them
    // unchanged does nothing (a status frame refreshes every label, and
    // formatting a hundred values and tool tips is a millisecond).
    struct Facts {
        std::optional<rcm::Value> reported;
        std::optional<rcm::Value> commanded;
        std::optional<int> staleSeconds;
        int mismatchFrames = 0;
        bool mismatch = false;
        friend bool operator==(const Facts&, const Facts&) = default;
    };
    std::optional<Facts> m_shown;

    const CommandState* m_command;
    const ReportedState* m_reported;
    UnitRef m_ref;
    rcm::ItemId m_id;
    int m_field;
    bool m_ageShown = true;
};
