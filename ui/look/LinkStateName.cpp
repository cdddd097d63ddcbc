#include "ui/look/LinkStateName.h"

#include <QCoreApplication>

QString linkStateName(LinkState state)
{
    switch (state) {
        case LinkState::Closed:
            return QCoreApplication::translate("LinkState", "Not connected");
        case LinkState::Waiting:
            return QCoreApplication::translate("LinkState", "Waiting for the aircraft");
        case LinkState::Connected:
            return QCoreApplication::translate("LinkState", "Connected");
        case LinkState::Lost:
            return QCoreApplication::translate("LinkState", "Lost");
    }
    return {};
}
