#pragma once

// A session seen from elsewhere, read only: another station's link told as
// the link's own events (LinkEvents), so that the console binds the same
// widgets to it as to a link of its own. It has no way to send anything to
// the aircraft. ConsoleSession runs one as its Observation kind, in the GUI
// thread; BrokerObservation is the one there is (a station's session on a
// broker).

#include "link/session/LinkEvents.h"

class Observation : public LinkEvents {
    Q_OBJECT

public:
    using LinkEvents::LinkEvents;

    virtual void start() = 0;
    virtual void stop() = 0;
    // What is observed, for people: the aircraft ("GB_133").
    virtual QString observed() const = 0;
};
