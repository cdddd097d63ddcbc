// The message header the operator sets: which aircraft is commanded
// (ID_UA_source) and the GCS stations it reports to (destination and backup).
// A station with no country is not sent. ID_msg and the UTC time and date are
// the link's to fill in, frame by frame.
#pragma once

#include <QWidget>

class CommandState;
class ReportedState;

class HeaderPanel : public QWidget {
    Q_OBJECT

public:
    HeaderPanel(CommandState* command, ReportedState* reported, QWidget* parent = nullptr);
};
