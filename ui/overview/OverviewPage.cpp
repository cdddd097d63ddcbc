#include "ui/overview/OverviewPage.h"

#include "ui/look/LinkStateName.h"
#include "ui/overview/LinkQualityPlot.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/ItemText.h"
#include "ui/panels/ReportedLabel.h"
#include "ui/panels/ReportedState.h"
#include "ui/panels/SteadyGroupBox.h"
#include "ui/panels/SteadyLabel.h"

#include <QDateTime>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLocale>
#include <QPainter>
#include <QResizeEvent>
#include <QScrollArea>
#include <QStyle>
#include <QVBoxLayout>

namespace {

QString fromView(std::string_view s)
{
    return QString::fromUtf8(s.data(), qsizetype(s.size()));
}

// "Engine 1", "Radio VHF1", "Camera NIK 1", "Flaps": the unit's label and,
// for a repeated unit, its key as the aircraft names it.
QString unitTitle(const CommandState& command, UnitRef ref)
{
    const QString label = fromView(rcm::unitLabel(ref.kind));
    const std::optional<rcm::ItemId> key = rcm::unitKey(ref.kind);
    if (!key)
        return label;
    const rcm::Value* value = command.value(ref, *key);
    return value ? label + QLatin1Char(' ') + ItemText::value(*key, *value) : label;
}

// Briefer than the status bar's names where the card's word would not fit.
QString stateName(LinkState state)
{
    if (state == LinkState::Waiting)
        return OverviewPage::tr("Waiting");
    if (state == LinkState::Lost)
        return OverviewPage::tr("LINK LOST");
    return linkStateName(state);
}

// The state word's colour: dark tones on a light window, light tones on a
// dark (night) one, each over 4.5:1 against its background; none when closed.
QString stateColour(LinkState state, bool replay, bool dark)
{
    if (replay)
        return dark ? QStringLiteral("#90caf9") : QStringLiteral("#0d47a1");
    switch (state) {
    case LinkState::Connected:
        return dark ? QStringLiteral("#81c784") : QStringLiteral("#1b5e20");
    case LinkState::Lost:
        return dark ? QStringLiteral("#ef9a9a") : QStringLiteral("#b71c1c");
    case LinkState::Waiting:
        return dark ? QStringLiteral("#ffd54f") : QStringLiteral("#6d4c00");
    case LinkState::Closed:
        break;
    }
    return {};
}

// An item's name in a card: whole when the card has the room, else cut with
// an ellipsis (whole in the tool tip), never widening the card.
class NameLabel : public QLabel {
public:
    NameLabel(const QString& text, QWidget* parent) : QLabel(text, parent) {}

    QSize minimumSizeHint() const override
    {
        return {fontMetrics().horizontalAdvance(QStringLiteral("Xxxx…")), QLabel::minimumSizeHint().height()};
    }

protected:
    void paintEvent(QPaintEvent*) override
    {
        QPainter painter(this);
        const QRect room = contentsRect();
        painter.setPen(palette().color(foregroundRole()));
        painter.drawText(room, Qt::AlignLeft | Qt::AlignVCenter,
                         fontMetrics().elidedText(text(), Qt::ElideRight, room.width()));
    }
};

}  // namespace

OverviewPage::OverviewPage(CommandState* command, ReportedState* reported, QWidget* parent)
    : QWidget(parent),
      m_command(command),
      m_reported(reported),
      m_clock([] { return QDateTime::currentMSecsSinceEpoch() * 1000; }),
      m_unitArea(new QWidget),
      m_unitColumns(new QHBoxLayout(m_unitArea)),
      m_plot(new LinkQualityPlot(&m_history))
{
    setObjectName(QStringLiteral("overview"));
    m_unitColumns->setContentsMargins(0, 0, 0, 0);
    m_unitColumns->setSpacing(kCardSpacing);
    auto* scroll = new QScrollArea;
    // The cards a little smaller than the page's text: every unit at a glance
    // on a 1366x768 screen, four cards to a row.
    QFont cardFont = font();
    cardFont.setPointSizeF(cardFont.pointSizeF() * 0.9);
    m_unitArea->setFont(cardFont);
    scroll->setWidget(m_unitArea);
    scroll->setWidgetResizable(true);
    scroll->setFrameShape(QFrame::NoFrame);
    scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);

    // The figures and the plot side by side on a wide page, so that the
    // cards keep the height; one over the other on a narrow one.
    m_top = new QBoxLayout(QBoxLayout::LeftToRight);
    m_top->setSpacing(8);
    m_top->addWidget(buildHealth(), 3);
    m_top->addWidget(m_plot, 2);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(6, 6, 6, 6);
    layout->setSpacing(6);
    layout->addLayout(m_top);
    layout->addWidget(scroll, 1);

    reflowFigures();
    rebuildUnits();
    connect(command, &CommandState::airframeChanged, this, &OverviewPage::rebuildUnits);
    connect(command, &CommandState::changed, this, &OverviewPage::refreshCommanded);
    m_timer.setInterval(1000);
    connect(&m_timer, &QTimer::timeout, this, &OverviewPage::tick);
    m_timer.start();
    m_plot->setNow(m_clock());
    updateFigures();
}

QWidget* OverviewPage::buildHealth()
{
    auto* box = new QFrame;
    box->setObjectName(QStringLiteral("linkHealth"));
    box->setFrameShape(QFrame::StyledPanel);
    // Ignored: the page's width decides how many figures go to a row
    // (reflowFigures()), never the other way round.
    box->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    box->installEventFilter(this);
    m_healthGrid = new QGridLayout(box);
    m_healthGrid->setContentsMargins(10, 6, 10, 6);
    m_healthGrid->setHorizontalSpacing(18);
    m_healthGrid->setVerticalSpacing(4);
    const struct {
        const char* name;
        QString caption;
        QString toolTip;
    } figures[] = {
        {"state", tr("Link"), tr("The link's state")},
        {"sent", tr("Frames sent"), tr("Command frames handed to the link since it started")},
        {"received", tr("Frames received"), tr("Good status frames from the aircraft")},
        {"corrected", tr("Corrected bytes"), tr("Bytes Reed-Solomon corrected in the frames received")},
        {"uncorrectable", tr("Beyond correction"), tr("Frames received with a codeword beyond correction")},
        {"refused", tr("Refused"),
         tr("Frames that decoded but were refused: forged, replayed, stale time or plaintext on a keyed link, "
            "and datagrams of the wrong size")},
        {"age", tr("Last frame"), tr("Time since the last good frame from the aircraft")},
    };
    QFont big = font();
    big.setBold(true);
    big.setPointSizeF(big.pointSizeF() * 1.4);
    for (const auto& f : figures) {
        auto* figureBox = new QWidget;
        auto* stack = new QVBoxLayout(figureBox);
        stack->setContentsMargins(0, 0, 0, 0);
        stack->setSpacing(0);
        auto* caption = new QLabel(f.caption);
        auto* value = new SteadyLabel;
        value->setObjectName(QStringLiteral("figure:") + QLatin1String(f.name));
        value->setFont(big);
        value->setTextFormat(Qt::PlainText);  // a new text each frame: no document to parse and lay out
        figureBox->setToolTip(f.toolTip);
        stack->addWidget(caption);
        stack->addWidget(value);
        m_figures.emplace_back(QLatin1String(f.name), value);
        m_figureBoxes.push_back(figureBox);
    }
    return box;
}

void OverviewPage::setClock(Clock clock)
{
    m_clock = std::move(clock);
    m_plot->setNow(m_clock());
    updateFigures();
}

QString OverviewPage::figure(const QString& name) const
{
    for (const auto& [n, label] : m_figures)
        if (n == name)
            return label->text();
    return {};
}

void OverviewPage::setStatistics(const LinkStatistics& statistics)
{
    const bool closedNow = statistics.state == LinkState::Closed && m_statistics.state != LinkState::Closed;
    m_statistics = statistics;
    if (m_replay && m_replayTime)
        // The log's statistics arrive after its time: sampled only at the next
        // time step, the last frames of a replay would never reach the plot.
        m_history.sample(m_replayTime, statistics);
    else if (closedNow)
        m_history.sample(m_clock(), statistics);  // nothing: closed adds nothing, but ends the count
    updateFigures();
}

void OverviewPage::setReplay(bool replay)
{
    // The plot shows one session's minutes: the log's during a replay, never
    // the live link's before it, and the next link's after.
    if (replay != m_replay) {
        m_history.clear();
        m_plot->update();
    }
    m_replay = replay;
    m_replayTime = 0;
    updateFigures();
}

void OverviewPage::setReplayTime(qint64 utcMicros)
{
    m_replayTime = utcMicros;
    // The log's statistics at the log's time: its minutes, on its own time axis.
    if (m_replay && utcMicros) {
        m_history.sample(utcMicros, m_statistics);
        m_plot->setNow(utcMicros);
    }
    updateFigures();
}

void OverviewPage::tick()
{
    const qint64 now = m_clock();
    if (!m_replay) {
        m_history.sample(now, m_statistics);
        m_plot->setNow(now);
    }
    updateFigures();
}

void OverviewPage::updateFigures()
{
    const QLocale locale;
    const LinkStatistics& s = m_statistics;
    const auto label = [this](const char* name) -> QLabel* {
        for (auto& [n, figure] : m_figures)
            if (n == QLatin1String(name))
                return figure;
        return nullptr;
    };
    const auto set = [&label](const char* name, const QString& text) { label(name)->setText(text); };
    const bool dark = palette().color(QPalette::Window).lightness() < 128;
    const QString colour = stateColour(s.state, m_replay, dark);
    const QString state = m_replay ? tr("Replay") : stateName(s.state);
    set("state", state);
    if (colour != m_stateColour) {
        m_stateColour = colour;
        // An empty palette resolves nothing of its own: the page's colours.
        QPalette palette;
        if (!colour.isEmpty())
            palette.setColor(QPalette::WindowText, QColor(colour));
        label("state")->setPalette(palette);
    }
    set("sent", locale.toString(s.framesSent));
    set("received", locale.toString(s.framesReceived));
    set("corrected", locale.toString(s.correctedBytesBlock1 + s.correctedBytesBlock2));
    const quint64 uncorrectable = s.refusedFor(rcm::Refusal::Uncorrectable);
    set("uncorrectable", locale.toString(uncorrectable));
    set("refused", locale.toString(s.refusedTotal() - uncorrectable));
    QString age;
    if (m_replay) {
        age = m_replayTime ? tr("log %1 UTC").arg(QDateTime::fromMSecsSinceEpoch(m_replayTime / 1000, Qt::UTC)
                                                      .toString(QStringLiteral("HH:mm:ss")))
                           : QStringLiteral("\u2014");
    } else {
        const qint64 micros = s.lastGoodFrameAgeMicros(m_clock());
        age = micros < 0 ? QStringLiteral("\u2014") : tr("%1 s ago").arg(locale.toString(double(micros) / 1e6, 'f', 1));
    }
    set("age", age);
}

void OverviewPage::rebuildUnits()
{
    for (QGroupBox* card : m_cards)
        delete card;
    m_cards.clear();
    m_rows.clear();
    QFont captionFont = m_unitArea->font();
    captionFont.setItalic(true);  // a heading, told from the values by shape rather than a faint colour
    QFont titleFont = m_unitArea->font();
    titleFont.setBold(true);
    // Every card the same width, from the font rather than the values shown,
    // so that the number of columns follows the page's width alone: a name
    // cut to its room (whole in its tool tip) and two values of a dozen
    // characters each.
    const QFontMetrics metrics(m_unitArea->font());
    const int nameWidth = metrics.horizontalAdvance(QStringLiteral("Carburettor"));
    const int valueWidth = metrics.horizontalAdvance(QStringLiteral("Independent"));
    m_cardWidth = nameWidth + 2 * valueWidth + 2 * 8 + 2 * 5 + 4;
    // The reported value's least width is that of its longest word ("RETRACTED").
    m_cardWidth = std::max(m_cardWidth, nameWidth + valueWidth + metrics.horizontalAdvance(QStringLiteral("RETRACTED")) + 30);
    for (int k = 0; k < rcm::kUnitKindCount; ++k) {
        const auto kind = rcm::UnitKind(k);
        if (kind == rcm::UnitKind::Header)
            continue;  // who talks to whom, not what the aircraft does: the Header panel has it
        for (int index = 0; index < m_command->unitCount(kind); ++index) {
            const UnitRef ref{kind, index};
            // A frame without a title: the unit's name is the first row's
            // first cell, beside the column headings, so no line goes to a
            // title of its own.
            const QString title = unitTitle(*m_command, ref);
            auto* card = new SteadyGroupBox(QString());
            card->setObjectName(QStringLiteral("overview:") + title);
            card->setFont(m_unitArea->font());  // before its labels are made: they measure their values in it
            auto* grid = new QGridLayout(card);
            grid->setContentsMargins(5, 2, 5, 3);
            grid->setHorizontalSpacing(8);
            grid->setVerticalSpacing(0);
            auto* name = new QLabel(title, card);
            name->setObjectName(QStringLiteral("title"));
            name->setFont(titleFont);
            grid->addWidget(name, 0, 0);
            int column = 1;
            for (const QString& heading : {tr("Commanded"), tr("Reported")}) {
                auto* label = new QLabel(heading, card);
                label->setObjectName(QStringLiteral("heading:") + heading);
                label->setFont(captionFont);
                grid->addWidget(label, 0, column++);
            }
            int row = 1;
            for (const rcm::ItemInfo& info : rcm::itemTable()) {
                if (info.owner != kind || info.key || !m_command->value(ref, info.id))
                    continue;
                const int fields = info.kind == rcm::ValueKind::Fields ? int(info.fields.size()) : 0;
                for (int field = fields ? 0 : -1; field < fields; ++field) {
                    const QString label = ItemText::label(info.id, field);
                    auto* name = new NameLabel(label, card);
                    name->setSizePolicy(QSizePolicy::Preferred, QSizePolicy::Preferred);
                    name->setToolTip(field < 0 ? ItemText::toolTip(info.id) : ItemText::fieldToolTip(info.id, field));
                    auto* commanded = new SteadyLabel(card);
                    commanded->setObjectName(QStringLiteral("commanded:") + ItemText::name(info.id, field));
                    auto* reported = new ReportedLabel(m_command, m_reported, ref, info.id, field, card);
                    reported->setAgeShown(false);  // the look says stale; the age is the figure above, and the tool tip's
                    grid->addWidget(name, row, 0);
                    grid->addWidget(commanded, row, 1);
                    grid->addWidget(reported, row, 2);
                    m_rows.push_back({ref, info.id, field, commanded, reported, std::nullopt, false});
                    ++row;
                }
            }
            // The names take the card's spare width, and are cut only when it has none.
            grid->setColumnStretch(0, 1);
            m_cards.push_back(card);
        }
    }
    refreshCommanded();
    m_columns = 0;  // lay out anew
    reflow();
}

void OverviewPage::refreshCommanded()
{
    for (Row& row : m_rows) {
        const rcm::Value* v = m_command->value(row.ref, row.id);
        const std::optional<rcm::Value> now = v ? std::optional(*v) : std::nullopt;
        if (row.shownOnce && now == row.shown)
            continue;
        row.shown = now;
        row.shownOnce = true;
        row.commanded->setText(!v ? QStringLiteral("\u2014")
                               : row.field < 0 ? ItemText::value(row.id, *v)
                                               : ItemText::fieldValue(row.id, row.field, *v, m_command->unit(row.ref)));
    }
}

void OverviewPage::resizeEvent(QResizeEvent* event)
{
    QWidget::resizeEvent(event);
    m_top->setDirection(width() >= kSideBySideWidth ? QBoxLayout::LeftToRight : QBoxLayout::TopToBottom);
    reflow();
}

void OverviewPage::changeEvent(QEvent* event)
{
    QWidget::changeEvent(event);
    if (event->type() == QEvent::PaletteChange)
        updateFigures();  // the night theme's colours for the state
}

bool OverviewPage::eventFilter(QObject* watched, QEvent* event)
{
    if (event->type() == QEvent::Resize && watched == m_healthGrid->parentWidget())
        reflowFigures();
    return QWidget::eventFilter(watched, event);
}

void OverviewPage::reflowFigures()
{
    // The figures: in as few rows as the width holds, each column as wide
    // as its widest figure.
    const int figureCount = int(m_figureBoxes.size());
    const int room = m_healthGrid->parentWidget()->width() - 20;
    int perRow = 1;
    for (int n = figureCount; n > 1; --n) {
        const int rows = (figureCount + n - 1) / n;
        const int even = (figureCount + rows - 1) / rows;  // rows of equal count
        int needed = 0;
        for (int c = 0; c < even; ++c) {
            int widest = 0;
            for (int i = c; i < figureCount; i += even)
                widest = std::max(widest, m_figureBoxes[std::size_t(i)]->sizeHint().width());
            needed += widest + (c ? 18 : 0);
        }
        if (needed <= room) {
            perRow = even;
            break;
        }
    }
    if (perRow != m_figuresPerRow) {
        m_figuresPerRow = perRow;
        for (int i = 0; i < figureCount; ++i) {
            m_healthGrid->removeWidget(m_figureBoxes[std::size_t(i)]);
            m_healthGrid->addWidget(m_figureBoxes[std::size_t(i)], i / perRow, i % perRow);
        }
        for (int c = 0; c <= figureCount; ++c)
            m_healthGrid->setColumnStretch(c, c == perRow ? 1 : 0);
    }
}

std::vector<int> OverviewPage::columnHeights(int columns, std::vector<std::size_t>* placed) const
{
    // Cards in order, each into the shortest column so far.
    std::vector<int> heights(std::size_t(columns), 0);
    for (QGroupBox* card : m_cards) {
        const auto shortest = std::size_t(std::min_element(heights.begin(), heights.end()) - heights.begin());
        if (placed)
            placed->push_back(shortest);
        heights[shortest] += card->sizeHint().height() + kCardSpacing;
    }
    return heights;
}

void OverviewPage::reflow()
{
    // From the page's size and the cards' sizes alone, never from the
    // values shown, so that a stale mark or a long value cannot make the
    // columns switch: as many as the width holds at most, and of those the
    // fewest in which every card shows without scrolling (the widest cards,
    // whose names are cut least).
    const int available = std::max(1, width() - 12 - style()->pixelMetric(QStyle::PM_ScrollBarExtent));
    const int widest =
        std::max(1, std::min<int>(int(m_cards.size()), (available + kCardSpacing) / (m_cardWidth + kCardSpacing)));
    const int room = height() - 18 - m_top->sizeHint().height();
    int columns = widest;
    for (int c = 1; c < widest; ++c) {
        const std::vector<int> heights = columnHeights(c, nullptr);
        if (*std::max_element(heights.begin(), heights.end()) <= room) {
            columns = c;
            break;
        }
    }
    if (columns == m_columns)
        return;
    m_columns = columns;
    // The column layouts go; the cards in them stay, children of the area.
    while (QLayoutItem* item = m_unitColumns->takeAt(0))
        delete item;
    std::vector<QVBoxLayout*> stacks;
    for (int c = 0; c < columns; ++c) {
        auto* stack = new QVBoxLayout;
        stack->setSpacing(kCardSpacing);
        m_unitColumns->addLayout(stack, 1);
        stacks.push_back(stack);
    }
    std::vector<std::size_t> placed;
    columnHeights(columns, &placed);
    for (std::size_t i = 0; i < m_cards.size(); ++i)
        stacks[placed[i]]->addWidget(m_cards[i]);
    for (QVBoxLayout* stack : stacks)
        stack->addStretch(1);
}

const OverviewPage::Row* OverviewPage::findRow(UnitRef ref, rcm::ItemId id, int field) const
{
    for (const Row& row : m_rows)
        if (row.ref == ref && row.id == id && row.field == field)
            return &row;
    return nullptr;
}

QString OverviewPage::commandedText(UnitRef ref, rcm::ItemId id, int field) const
{
    const Row* row = findRow(ref, id, field);
    return row ? row->commanded->text() : QString();
}

ReportedLabel* OverviewPage::reportedLabel(UnitRef ref, rcm::ItemId id, int field) const
{
    const Row* row = findRow(ref, id, field);
    return row ? row->reported : nullptr;
}
