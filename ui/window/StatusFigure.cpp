#include "ui/window/StatusFigure.h"

#include "ui/panels/SteadyLabel.h"

#include <QHBoxLayout>
#include <QLabel>

StatusFigure::StatusFigure(const QString& name, const QString& toolTip, QWidget* parent)
    : QWidget(parent), m_name(new QLabel(name)), m_value(new SteadyLabel)
{
    setToolTip(toolTip);
    for (QLabel* label : {static_cast<QLabel*>(m_name), static_cast<QLabel*>(m_value)})
        label->setTextFormat(Qt::PlainText);
    QPalette grey = m_name->palette();
    grey.setColor(QPalette::WindowText, QColor(0x6b, 0x6b, 0x6b));
    m_name->setPalette(grey);
    QFont bold = m_value->font();
    bold.setBold(true);
    m_value->setFont(bold);
    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->setSpacing(fontMetrics().horizontalAdvance(QLatin1Char(' ')));
    layout->addWidget(m_name);
    layout->addWidget(m_value);
}

void StatusFigure::setName(const QString& name)
{
    m_name->setText(name);
}

void StatusFigure::setValue(const QString& value)
{
    m_value->setText(value);
}

void StatusFigure::setValueColour(const QColor& colour)
{
    if (colour == m_colour)
        return;
    m_colour = colour;
    // An empty palette resolves nothing of its own: the window's colours.
    QPalette palette;
    if (colour.isValid())
        palette.setColor(QPalette::WindowText, colour);
    m_value->setPalette(palette);
}

QString StatusFigure::text() const
{
    return m_name->text() + QLatin1Char(' ') + m_value->text();
}

QString StatusFigure::value() const
{
    return m_value->text();
}
