#pragma once
// Console logging for the `grip` executable: one spdlog logger on stderr, its level set by
// -v / -q / --log-level.
#include <string>

namespace grip {

// level: one of trace, debug, info, warn, error, critical, off. Throws std::invalid_argument
// naming the allowed levels otherwise.
void configure_logging(const std::string& level);

}  // namespace grip
