#pragma once

// A pseudo-terminal pair for a program to open as its serial port (a
// rehearsal's line, the satellite modem model's sides), raw from the start:
// a new pty echoes, and would hand a program's bytes back to it as if the far
// end had said them. The master is non-blocking and neither end is inherited
// by programs the host starts, so that a slave held here never looks held by
// them.

#include <QString>

struct PseudoTerminal {
    int master = -1;
    int slave = -1;
    QString device;  // the slave's path, "/dev/pts/N"
};

// Nothing opened, and the reason in *error, when the system refuses.
bool openRawPseudoTerminal(PseudoTerminal& pty, QString* error);
