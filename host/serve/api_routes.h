#pragma once
// The /api/ endpoints. Handlers throw BadRequest or InputError for a 400 with the message; frames
// that failed to shade answer 422 with the shading error.
#include <map>
#include <mutex>
#include <string>

#include "serve/http_router.h"
#include "serve/live_relighter.h"
#include "serve/query.h"
#include "serve/relight_server.h"

namespace phongcl {

struct ImageRequest;

class ApiRoutes {
 public:
  ApiRoutes(LiveRelighter& live, const ServeOptions& options) : live_(live), options_(options) {}
  void add_to(HttpRouter& router);

 private:
  void get_scene(const HttpRequest& request, HttpResponse& response);
  void put_scene(const HttpRequest& request, HttpResponse& response);
  void get_settings(const HttpRequest& request, HttpResponse& response);
  void put_settings(const HttpRequest& request, HttpResponse& response);
  void get_image(const HttpRequest& request, HttpResponse& response);
  void get_frame(const HttpRequest& request, HttpResponse& response);
  void get_stats(const HttpRequest& request, HttpResponse& response);
  void get_pick(const HttpRequest& request, HttpResponse& response);
  void post_save(const HttpRequest& request, HttpResponse& response);
  void get_beauty(const HttpRequest& request, HttpResponse& response);
  void get_colors(const HttpRequest& request, HttpResponse& response);
  void get_color(const HttpRequest& request, HttpResponse& response);
  void send_frame(const ImageRequest& wanted, const RenderedFrame& frame, HttpResponse& response);
  void send_image(const ImageRequest& wanted, const Image& image, const glm::dvec3& background, HttpResponse& response);

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

}  // namespace phongcl
