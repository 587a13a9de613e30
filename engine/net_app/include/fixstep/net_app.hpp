// fixstep::net_app, all of it: a game of app::run networked from its command line: net::run.
// One include for a program that uses the whole library; each header below stands alone.
#pragma once

#include "fixstep/net_app/run.hpp"
