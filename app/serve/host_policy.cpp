// hotmesh serve: the Host and Origin check (see host_policy.hpp).
#include "serve/host_policy.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/core/text.hpp"
#include "service/api_error.hpp"

namespace hotmesh::app::serve {

namespace {

/// An IP address in its canonical text, if `text` is one.
std::optional<std::string> canonical_address(const std::string& text, int family) {
  unsigned char binary[sizeof(in6_addr)];
  char canonical[INET6_ADDRSTRLEN];
  if (::inet_pton(family, text.c_str(), binary) != 1) return std::nullopt;
  if (::inet_ntop(family, binary, canonical, sizeof canonical) == nullptr) return std::nullopt;
  return std::string(canonical);
}

/// A client's value as shown in a message: at most 100 characters.
std::string shown(std::string_view value) {
  return value.size() <= 100 ? std::string(value) : fmt::format("{}...", value.substr(0, 100));
}

bool wildcard(std::string_view bind) { return bind.empty() || bind == "0.0.0.0" || bind == "::" || bind == "[::]"; }

/// The host names and addresses of this machine: its name, the addresses of its interfaces.
std::vector<std::string> machine_names() {
  std::vector<std::string> names;
  char name[256] = "";
  if (::gethostname(name, sizeof name - 1) == 0 && name[0] != '\0') names.emplace_back(name);
  ifaddrs* list = nullptr;
  if (::getifaddrs(&list) != 0) return names;
  for (const ifaddrs* a = list; a != nullptr; a = a->ifa_next) {
    if (a->ifa_addr == nullptr || (a->ifa_addr->sa_family != AF_INET && a->ifa_addr->sa_family != AF_INET6)) continue;
    const socklen_t length = a->ifa_addr->sa_family == AF_INET ? sizeof(sockaddr_in) : sizeof(sockaddr_in6);
    char host[NI_MAXHOST] = "";
    if (::getnameinfo(a->ifa_addr, length, host, sizeof host, nullptr, 0, NI_NUMERICHOST) != 0) continue;
    std::string text(host);
    text = text.substr(0, text.find('%'));  // no zone of a link-local address: browsers send none
    names.push_back(a->ifa_addr->sa_family == AF_INET6 ? "[" + text + "]" : text);
  }
  ::freeifaddrs(list);
  return names;
}

}  // namespace

std::optional<std::string> normalized_host(std::string_view host, int default_port) {
  std::string name;
  std::string_view rest;
  if (host.starts_with('[')) {
    const auto close = host.find(']');
    if (close == std::string_view::npos) return std::nullopt;
    const auto address = canonical_address(std::string(host.substr(1, close - 1)), AF_INET6);
    if (!address) return std::nullopt;
    name = "[" + *address + "]";
    rest = host.substr(close + 1);
  } else {
    const auto colon = host.find(':');
    name = std::string(host.substr(0, colon));
    rest = colon == std::string_view::npos ? std::string_view() : host.substr(colon);
    const bool valid = !name.empty() && std::all_of(name.begin(), name.end(), [](unsigned char c) {
      return std::isalnum(c) || c == '.' || c == '-' || c == '_';
    });
    if (!valid) return std::nullopt;
    name = ascii_lower(name);
    if (const auto address = canonical_address(name, AF_INET)) name = *address;
  }
  int port = default_port;
  if (!rest.empty()) {
    const std::string_view digits = rest.substr(1);
    const bool valid = rest.front() == ':' && !digits.empty() && digits.size() <= 5 &&
                       std::all_of(digits.begin(), digits.end(), [](unsigned char c) { return std::isdigit(c); });
    if (!valid) return std::nullopt;
    port = std::stoi(std::string(digits));
    if (port < 1 || port > 65535) return std::nullopt;
  }
  return fmt::format("{}:{}", name, port);
}

HostPolicy::HostPolicy(std::string_view bind, int port, const std::vector<std::string>& extra) {
  std::vector<std::string> names{"localhost", "127.0.0.1", "[::1]"};
  if (wildcard(bind)) {
    const std::vector<std::string> machine = machine_names();
    names.insert(names.end(), machine.begin(), machine.end());
  } else {
    const bool bare_ipv6 = bind.find(':') != std::string_view::npos && !bind.starts_with('[');
    names.push_back(bare_ipv6 ? fmt::format("[{}]", bind) : std::string(bind));
  }
  for (const std::string& name : names) {
    if (const auto host = normalized_host(name, port)) hosts_.insert(*host);
  }
  for (const std::string& name : extra) {
    const auto host = normalized_host(name, port);
    if (!host) {
      throw InputError(fmt::format("--allow-host: '{}' is not a host name or address with an optional port "
                                   "(NAME, NAME:PORT, [IPv6]:PORT)",
                                   shown(name)));
    }
    hosts_.insert(*host);
  }
}

void HostPolicy::check(const std::optional<std::string>& host, const std::optional<std::string>& origin) const {
  if (!host) throw ApiError::bad_request("Host: the request has no Host header (HTTP/1.1 requires one)");
  const auto ours = normalized_host(*host, 80);
  if (!ours || !hosts_.contains(*ours)) {
    throw ApiError::forbidden(fmt::format(
        "Host '{}' is not a name of this service: it answers to {} (hotmesh serve --allow-host NAME adds a name)",
        shown(*host), fmt::join(hosts_, ", ")));
  }
  if (!origin) return;
  // Same origin only: the page the browser shows came from this very Host.
  constexpr std::string_view kScheme = "http://";
  const std::string_view text = *origin;
  const bool http = text.size() > kScheme.size() && ascii_lower(text.substr(0, kScheme.size())) == kScheme;
  const auto from = http ? normalized_host(text.substr(kScheme.size()), 80) : std::nullopt;
  if (!from || *from != *ours) {
    throw ApiError::forbidden(fmt::format("Origin '{}' is not this service (http://{}): requests from pages of other "
                                          "sites are refused",
                                          shown(*origin), shown(*host)));
  }
}

}  // namespace hotmesh::app::serve
