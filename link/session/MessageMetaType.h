#pragma once

// rcm::Message as a Qt meta type, for queued signals. Declared once, here,
// and included by every header that names rcm::Message in a signal or slot:
// a moc file that sees the type before this declaration would instantiate a
// conflicting default.

#include "codec/message/Message.h"

#include <QMetaType>

Q_DECLARE_METATYPE(rcm::Message)
