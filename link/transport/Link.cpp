#include "link/transport/Link.h"

Link::Link(QObject* parent) : QObject(parent) {}

Link::~Link() = default;
