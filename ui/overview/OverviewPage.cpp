#include "ui/overview/OverviewPage.h"

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

QString stateName(LinkState state)
{
    switch (state) {
    case LinkState::Closed:
        return OverviewPage::tr("Not connected");
    case LinkState::Waiting:
        return OverviewPage::tr("Waiting");
    case LinkState::Connected:
        return OverviewPage::tr("Connected");
    case LinkState::Lost:
        return OverviewPage::tr("LINK LOST");
    }
    return {};
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
    m_unitColumns->setSpacing(8);
    auto* scroll = new QScrollArea;
    scroll->setWidget(m_unitArea);
    scroll->setWidgetResizable(true);
    scroll->setFrameShape(QFrame::NoFrame);
    scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);

    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(6, 6, 6, 6);
    layout->addWidget(buildHealth());
    layout->addWidget(scroll, 1);
    layout->addWidget(m_plot);

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
    if (closedNow)
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
    QFont captionFont = font();
    captionFont.setPointSizeF(captionFont.pointSizeF() * 0.9);
    captionFont.setItalic(true);  // a heading, told from the values by shape rather than a faint colour
    for (int k = 0; k < rcm::kUnitKindCount; ++k) {
        const auto kind = rcm::UnitKind(k);
        if (kind == rcm::UnitKind::Header)
            continue;  // who talks to whom, not what the aircraft does: the Header panel has it
        for (int index = 0; index < m_command->unitCount(kind); ++index) {
            const UnitRef ref{kind, index};
            auto* card = new SteadyGroupBox(unitTitle(*m_command, ref));
            card->setObjectName(QStringLiteral("overview:") + card->title());
            auto* grid = new QGridLayout(card);
            grid->setContentsMargins(6, 4, 6, 4);
            grid->setHorizontalSpacing(10);
            grid->setVerticalSpacing(1);
            int column = 1;
            for (const QString& heading : {tr("Commanded"), tr("Reported")}) {
                auto* label = new QLabel(heading);
                label->setFont(captionFont);
                grid->addWidget(label, 0, column++);
            }
            int row = 1;
            for (const rcm::ItemInfo& info : rcm::itemTable()) {
                if (info.owner != kind || info.key || !m_command->value(ref, info.id))
                    continue;
                const int fields = info.kind == rcm::ValueKind::Fields ? int(info.fields.size()) : 0;
                for (int field = fields ? 0 : -1; field < fields; ++field) {
                    auto* name = new QLabel(ItemText::label(info.id, field));
                    name->setToolTip(field < 0 ? ItemText::toolTip(info.id) : ItemText::fieldToolTip(info.id, field));
                    auto* commanded = new SteadyLabel;
                    commanded->setObjectName(QStringLiteral("commanded:") + ItemText::name(info.id, field));
                    auto* reported = new ReportedLabel(m_command, m_reported, ref, info.id, field);
                    grid->addWidget(name, row, 0);
                    grid->addWidget(commanded, row, 1);
                    grid->addWidget(reported, row, 2);
                    m_rows.push_back({ref, info.id, field, commanded, reported, std::nullopt, false});
                    ++row;
                }
            }
            // Values right beside their names; the card's spare width after them.
            grid->setColumnStretch(3, 1);
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
                                               : ItemText::fieldValue(row.id, row.field, *v));
    }
}

void OverviewPage::resizeEvent(QResizeEvent* event)
{
    QWidget::resizeEvent(event);
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
    // The figures: as many to a row as fit, in rows of equal count.
    int figureWidth = 1;
    for (QWidget* box : m_figureBoxes)
        figureWidth = std::max(figureWidth, box->sizeHint().width());
    const int figureCount = int(m_figureBoxes.size());
    const int fit = std::clamp((m_healthGrid->parentWidget()->width() - 20) / (figureWidth + 18), 1, figureCount);
    const int perRow = (figureCount + (figureCount + fit - 1) / fit - 1) / ((figureCount + fit - 1) / fit);
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

void OverviewPage::reflow()
{
    int cardWidth = 1;
    for (QGroupBox* card : m_cards)
        cardWidth = std::max(cardWidth, card->sizeHint().width());
    const int available = std::max(1, width() - 12 - style()->pixelMetric(QStyle::PM_ScrollBarExtent));
    const int columns = std::max(1, std::min<int>(int(m_cards.size()), (available + 8) / (cardWidth + 8)));
    if (columns == m_columns)
        return;
    m_columns = columns;
    // Cards in order, each into the shortest column so far.
    // The column layouts go; the cards in them stay, children of the area.
    while (QLayoutItem* item = m_unitColumns->takeAt(0))
        delete item;
    std::vector<QVBoxLayout*> stacks;
    std::vector<int> heights(std::size_t(columns), 0);
    for (int c = 0; c < columns; ++c) {
        auto* stack = new QVBoxLayout;
        stack->setSpacing(8);
        m_unitColumns->addLayout(stack, 1);
        stacks.push_back(stack);
    }
    for (QGroupBox* card : m_cards) {
        const auto shortest = std::size_t(std::min_element(heights.begin(), heights.end()) - heights.begin());
        stacks[shortest]->addWidget(card);
        heights[shortest] += card->sizeHint().height();
    }
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
