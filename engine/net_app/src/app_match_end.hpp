// Internal to fixstep::net_app: how a peer's match ends: it lingers until the others have what
// they need, locates a desync, keeps its desync files, and sums up the match.
#pragma once

#include <string>

#include "fixstep/net/match_peer.hpp"

namespace fixstep::net::detail {

/// Where a match without --record streams its recording, in the working directory, to keep it
/// if the match desyncs (moved then to NAME-desync-pSLOT-tTICK.rec; else never published).
[[nodiscard]] std::string desync_file(const std::string& program);

/// Keeps the match answering after its end until every other peer has acknowledged every input
/// it needs from this one (MatchPeer::settled), and 600 ms more; at most the peer timeout
/// (MatchPeer::peer_timeout_ms, grown with the round trip). Then leaves. A wait past a second
/// says so on stderr, as program `name`, when stderr is a terminal.
void linger_and_leave(MatchPeer& m, const std::string& name);

/// A desync found: keeps answering until it is located (MatchPeer::locating), at most the peer
/// timeout (MatchPeer::peer_timeout_ms).
void locate_desync(MatchPeer& m);

/// A desync's state of its first differing tick, NAME-desync-pSLOT-tTICK.state in the working
/// directory (net::write_desync_state); says where on stderr, or why it was not written.
void keep_desync_state(const MatchPeer& m, const std::string& name);

/// A match without --record that desynced: its streamed recording moved to
/// NAME-desync-pSLOT-tTICK.rec in the working directory; says where on stderr.
void keep_desync_recording(MatchPeer& m, const std::string& name);

/// The match's line of the summary: who this peer was and what the network did.
[[nodiscard]] std::string match_summary(const MatchPeer& m);

}  // namespace fixstep::net::detail
