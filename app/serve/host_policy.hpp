// hotmesh serve: which requests come from a page the service may answer. A web page elsewhere
// can make the user's browser send requests to the service: through a name of its own that it
// points at this machine (DNS rebinding: the Host header then holds that name) or directly
// (cross-site: the Origin header names the other site). The service answers only requests
// whose Host is one of its own names with its port, and whose Origin, if any, is the service
// itself. Clients that are not browsers (curl, scripts) send no Origin and pass.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace hotmesh::app::serve {

class HostPolicy {
 public:
  /// The service listens on `bind` (an address or name, "0.0.0.0" or "::" for every address
  /// of the machine) at `port`. Its names: localhost, 127.0.0.1, [::1], the bound address; for
  /// every address, also this machine's host name and the addresses of its network interfaces;
  /// and `extra` (--allow-host): NAME or NAME:PORT (NAME alone: at the service's port).
  /// Throws hotmesh::InputError naming an entry of `extra` that is not a host name or address.
  HostPolicy(std::string_view bind, int port, const std::vector<std::string>& extra = {});

  /// Throws ApiError: 400 without a Host header, 403 for a Host that is not one of the
  /// service's names or an Origin other than the service.
  void check(const std::optional<std::string>& host, const std::optional<std::string>& origin) const;

  /// The accepted HOST:PORT values, sorted.
  const std::set<std::string>& hosts() const { return hosts_; }

 private:
  std::set<std::string> hosts_;
};

/// "NAME:PORT" in the form HostPolicy compares: the name in lower case, an IP address in its
/// canonical text (IPv6 in brackets), the port explicit (`default_port` if none is given).
/// Empty if `host` is not a host name or address with an optional port.
std::optional<std::string> normalized_host(std::string_view host, int default_port);

}  // namespace hotmesh::app::serve
