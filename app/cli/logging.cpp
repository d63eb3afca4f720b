#include "app/cli/logging.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <stdexcept>

namespace grip {

void configure_logging(const std::string& level) {
  const auto parsed = spdlog::level::from_str(level);
  // from_str maps every unknown name to "off"; only "off" itself may mean off.
  if (parsed == spdlog::level::off && level != "off") {
    throw std::invalid_argument("unknown log level '" + level +
                                "'; use one of trace, debug, info, warn, error, critical, off");
  }
  auto logger = spdlog::stderr_color_mt("grip");
  logger->set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");
  logger->set_level(parsed);
  spdlog::set_default_logger(logger);
}

}  // namespace grip
