// fixstep::capture, all of it: frames to files: PNG, video, the frame manifest.
// One include for a program that uses the whole library; each header below stands alone.
#pragma once

#include "fixstep/capture/capture.hpp"
#include "fixstep/capture/capture_dir.hpp"
#include "fixstep/capture/frame_pipeline.hpp"
#include "fixstep/capture/manifest.hpp"
#include "fixstep/capture/video.hpp"
#include "fixstep/capture/video_limits.hpp"
