#include "link/Link.h"

Link::Link(QObject* parent) : QObject(parent) {}

Link::~Link() = default;
