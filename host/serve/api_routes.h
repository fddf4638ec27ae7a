#pragma once
// The /api/ endpoints. Handlers throw BadRequest or InputError for a 400 with the message; frames
// that failed to shade answer 422 with the shading error.
#include <map>
#include <mutex>
#include <string>

#include <httplib.h>

#include "serve/live_relighter.h"
#include "serve/query.h"
#include "serve/relight_server.h"

namespace phongcl {

struct ImageRequest;

class ApiRoutes {
 public:
  ApiRoutes(LiveRelighter& live, const ServeOptions& options) : live_(live), options_(options) {}
  void add_to(httplib::Server& server);

 private:
  void get_scene(const httplib::Request& request, httplib::Response& response);
  void put_scene(const httplib::Request& request, httplib::Response& response);
  void get_settings(const httplib::Request& request, httplib::Response& response);
  void put_settings(const httplib::Request& request, httplib::Response& response);
  void get_image(const httplib::Request& request, httplib::Response& response);
  void get_frame(const httplib::Request& request, httplib::Response& response);
  void get_stats(const httplib::Request& request, httplib::Response& response);
  void get_pick(const httplib::Request& request, httplib::Response& response);
  void post_save(const httplib::Request& request, httplib::Response& response);
  void get_beauty(const httplib::Request& request, httplib::Response& response);
  void send_frame(const ImageRequest& wanted, const RenderedFrame& frame, httplib::Response& response);
  void send_image(const ImageRequest& wanted, const Image& image, httplib::Response& response);

  // Holds one of HttpLimits::max_waiting places for a request that waits for a frame, or throws
  // Unavailable (503) when all are taken: waiting requests never take every worker.
  class WaitingPlace {
   public:
    explicit WaitingPlace(ApiRoutes& routes);
    ~WaitingPlace();
    WaitingPlace(const WaitingPlace&) = delete;
    WaitingPlace& operator=(const WaitingPlace&) = delete;

   private:
    ApiRoutes& routes_;
  };

  LiveRelighter& live_;
  const ServeOptions& options_;
  std::mutex waiting_mutex_;
  std::size_t waiting_ = 0;  // guarded by waiting_mutex_
  std::mutex encode_mutex_;
  std::map<std::string, double> last_encode_ms_;  // by format; guarded by encode_mutex_
};

// {"error": message}
std::string error_json(const std::string& message);

}  // namespace phongcl
