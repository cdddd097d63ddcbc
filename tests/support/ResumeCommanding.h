// A console's window resumes commanding as its operator would: once the
// aircraft has been heard (its report in the panels), the band above the
// panels' Resume commanding (or Take control), confirmed. A new link holds
// the command back until then (issue 24, link/session/CommandHold.h).
#pragma once

#include "AnswerBox.h"

#include "link/session/ConsoleSession.h"
#include "ui/control/CommandHoldBar.h"
#include "ui/window/MainWindow.h"

#include <QPushButton>
#include <QTest>

namespace rcm::test {

// True once the window commands; false when nothing was heard from the
// aircraft within `timeoutMs`.
inline bool resumeCommanding(MainWindow& window, int timeoutMs)
{
    if (!QTest::qWaitFor([&] { return window.session()->commandHold()->reportHeard(); }, timeoutMs))
        return false;
    SeenBox seen;
    answerNextBox(&seen, false);
    window.commandHold()->resumeButton()->click();
    return window.session()->commanding();
}

}  // namespace rcm::test
