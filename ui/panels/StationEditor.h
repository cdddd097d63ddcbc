// Edits one station item (a country and a unit number: ID_UA_source, the GCS
// destination and backup, a camera's imagery stations) of one commanded unit.
// The country is typed as ISO alpha-2 ("GB") or as the dialling code ("44"),
// the unit as its number (0..65535). The two are one value, commanded only
// on Enter in either field and only when complete and valid. Tab from
// country to unit is still typing it: "edited", shown, not sent. A country
// without its unit number, a unit without its country, or a country that
// names no dialling code is marked incomplete, and the command keeps what it
// had meanwhile, so "GB" then Tab never sends GB_0. Leaving the editor before
// Enter (Tab or a click out of it, a tab switch, another window) sends
// nothing, not even a valid prefix of the station (GB_30 of GB_30226): both
// fields show the command again and say so, in their tool tips and through
// CommandGate::notSent(). Both fields empty and Enter: the item is not sent.
#pragma once

#include "codec/message/ItemTable.h"
#include "codec/message/Message.h"
#include "ui/panels/UnitRef.h"

#include <QWidget>

#include <cstdint>
#include <optional>

class CommandState;
class QLineEdit;

class StationEditor : public QWidget {
    Q_OBJECT

public:
    StationEditor(CommandState* command, UnitRef ref, rcm::ItemId id, QWidget* parent = nullptr);

    QLineEdit* countryEdit() const { return m_country; }
    QLineEdit* unitEdit() const { return m_unit; }
    rcm::ItemId item() const { return m_id; }
    // What was typed is not a station the command can take: not sent.
    bool incomplete() const { return property("incomplete").toBool(); }
    // Complete and valid, differs from the command, not sent yet.
    bool edited() const { return property("edited").toBool(); }
    // What the editor last said was not sent, empty after a commit or an edit.
    QString notSentText() const { return m_notSent; }

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    // What the two fields say: a station, nothing (both empty), or the field at fault and why.
    struct Typed {
        std::optional<rcm::Value> value;
        QLineEdit* atFault = nullptr;
        QString problem;
    };
    Typed typed() const;
    QString commandedText() const;
    void refresh();
    void commit();
    void fieldLeft(Qt::FocusReason reason);
    // A whole station typed and not sent yet is marked "edited" as it is typed.
    void showTyped();
    // Typed text left unsent: the command shown again, and said.
    void restoreUnsent();
    QString typedText() const;
    // Empty: what is typed is commanded. Otherwise why it is not, on the field at fault.
    void setProblem(QLineEdit* field, const QString& reason);
    static std::optional<std::int64_t> countryCode(const QString& text);

    CommandState* m_command;
    UnitRef m_ref;
    rcm::ItemId m_id;
    QLineEdit* m_country;
    QLineEdit* m_unit;
    QString m_notSent;
};
