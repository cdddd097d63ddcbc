#pragma once

// The names of an enumeration's values as one table, {value, name} a row,
// in place of a switch that says each case again: a table is read both
// ways, the name of a value and the value of a name, so that what a file
// writes and what it reads back cannot drift apart. Names are UTF-8
// literals. A class whose texts are for people marks them
// QT_TRANSLATE_NOOP("Class", ...) and passes the name through tr(), as it
// passed the literal before.
//
//   constexpr auto kNames = std::to_array<Named<Colour>>({{Colour::Red, "red"}, {Colour::Blue, "blue"}});
//   nameOf(kNames, Colour::Red) == "red";  valueIn(kNames, QStringLiteral("blue")) == Colour::Blue

#include <QString>

#include <array>
#include <cstddef>
#include <optional>

template <typename Value>
struct Named {
    Value value;
    const char* name;
};

template <typename Value, std::size_t N>
using NameTable = std::array<Named<Value>, N>;

// The name of `value`; nullptr when no row has it.
template <typename Value, std::size_t N>
constexpr const char* nameOf(const NameTable<Value, N>& table, Value value)
{
    for (const Named<Value>& row : table)
        if (row.value == value)
            return row.name;
    return nullptr;
}

// The same as a QString: a null one when no row has it.
template <typename Value, std::size_t N>
QString nameText(const NameTable<Value, N>& table, Value value)
{
    return QString::fromUtf8(nameOf(table, value));
}

// The value of the row named `name` (a QString, a QByteArray: anything that
// compares with a C string), compared exactly; nothing when no row has it.
template <typename Value, std::size_t N, typename Text>
std::optional<Value> valueIn(const NameTable<Value, N>& table, const Text& name)
{
    for (const Named<Value>& row : table)
        if (name == row.name)
            return row.value;
    return std::nullopt;
}
