// Edits one station item (a country and a unit number: ID_UA_source, the GCS
// destination and backup, a camera's imagery stations) of one commanded unit.
// The country is typed as ISO alpha-2 ("GB") or as the dialling code ("44");
// an empty country means the item is not sent. A country that names no
// dialling code is refused where it is typed, and the command keeps its value.
#pragma once

#include "codec/message/ItemTable.h"
#include "ui/panels/UnitRef.h"

#include <QWidget>

#include <cstdint>
#include <optional>

class CommandState;
class QLineEdit;
class QSpinBox;

class StationEditor : public QWidget {
    Q_OBJECT

public:
    StationEditor(CommandState* command, UnitRef ref, rcm::ItemId id, QWidget* parent = nullptr);

    QLineEdit* countryEdit() const { return m_country; }
    QSpinBox* unitSpinBox() const { return m_unit; }
    rcm::ItemId item() const { return m_id; }

private:
    void refresh();
    void commit();
    // Empty: the country is fine. Otherwise why it is not, shown on the country field.
    void setInvalid(const QString& reason);
    static std::optional<std::int64_t> countryCode(const QString& text);

    CommandState* m_command;
    UnitRef m_ref;
    rcm::ItemId m_id;
    QLineEdit* m_country;
    QSpinBox* m_unit;
};
