// fixstep::net, all of it: peers playing one match over UDP: packets, transport, lockstep and
// rollback, the link conditioner. One include for a program that uses the whole library; each
// header below stands alone.
#pragma once

#include "fixstep/net/desync_recording.hpp"
#include "fixstep/net/link_conditioner.hpp"
#include "fixstep/net/match_peer.hpp"
#include "fixstep/net/net_gate.hpp"
#include "fixstep/net/net_input_codec.hpp"
#include "fixstep/net/net_packet.hpp"
#include "fixstep/net/net_protocol.hpp"
#include "fixstep/net/net_transport.hpp"
