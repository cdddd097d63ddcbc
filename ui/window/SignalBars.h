#pragma once

// A satellite phone's signal as a phone shows it: five bars of rising height,
// as many filled as the phone reports (0..5), all hollow and crossed out when
// it is not registered with the network, grey when not known. The words
// ("registered, signal 3 of 5") are its tool tip and its accessible name.

#include <QWidget>

class SignalBars : public QWidget {
    Q_OBJECT

public:
    explicit SignalBars(QWidget* parent = nullptr);

    // bars 0..5, -1: not known.
    void setService(int bars, bool registered, const QString& text);
    int bars() const { return m_bars; }
    bool registered() const { return m_registered; }
    QString text() const { return m_text; }

    QSize sizeHint() const override;

protected:
    void paintEvent(QPaintEvent* event) override;

private:
    int m_bars = -1;
    bool m_registered = false;
    QString m_text;
};
