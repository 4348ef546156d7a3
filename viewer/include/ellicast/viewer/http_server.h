// A small HTTP/1.1 server for the live view: one thread, poll(2), non-blocking sockets. It serves
// GET requests from routes (each response sent whole, then the connection closed) and keeps
// Server-Sent Events streams open to push updates. Built for a page on the same machine: it binds
// to loopback unless told otherwise, refuses requests whose Host header names another site while
// bound to loopback (DNS rebinding), and bounds everything a client can make it hold.
// Knows nothing of ellicast streams or models.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace ellicast::viewer {

struct HttpResponse {
    int status = 200;
    std::string content_type = "text/plain; charset=utf-8";
    std::string body;
    bool no_store = false;  // Cache-Control: no-store (for content that changes)
};

HttpResponse http_error(int status, const std::string& message);

// The MIME type of a file name by its extension (application/octet-stream when unknown).
std::string content_type_for(const std::string& name);

// A file under `root` named by `relative` (a request path after its prefix): 404 when it does not
// exist, 403 for anything that could leave `root` (.., a leading /, a backslash, a control
// character, a component starting with a dot) or that is not a regular file, 413 past `max_bytes`.
HttpResponse file_response(const std::filesystem::path& root, const std::string& relative,
                           size_t max_bytes = size_t(64) << 20);

struct HttpLimits {
    size_t max_clients = 64;                     // connections held at once; more are closed at once
    size_t max_request_bytes = 16 << 10;         // request line and headers
    size_t max_event_backlog = size_t(8) << 20;  // bytes queued for one event-stream client
    std::chrono::seconds request_timeout{20};    // to send a whole request
};

class HttpServer {
public:
    using Handler = std::function<HttpResponse(const std::string& path, const std::string& query)>;

    HttpServer();
    ~HttpServer();
    HttpServer(const HttpServer&) = delete;
    HttpServer& operator=(const HttpServer&) = delete;

    // Listens on `address` (an IPv4 or IPv6 literal, or "localhost") and `port` (0: a free port the
    // system picks). False with `error` naming the address and the reason.
    bool listen(const std::string& address, uint16_t port, std::string& error, HttpLimits limits = {});
    uint16_t port() const { return port_; }
    // The address to give a browser: http://ADDRESS:PORT/ (IPv6 in brackets).
    std::string url() const;
    bool loopback() const { return loopback_; }

    // GET `path` exactly, or every path starting with `prefix`.
    void route(const std::string& path, Handler handler);
    void route_prefix(const std::string& prefix, Handler handler);
    // GET `path` opens an event stream; `greeting` gives the events a new client gets first (each
    // a pair: event name, data).
    void event_stream(const std::string& path,
                      std::function<std::vector<std::pair<std::string, std::string>>()> greeting);

    // Sends an event (name, one line of data) to every open event stream. A client that cannot keep
    // up (its backlog past the limit) is dropped; the page reconnects and is greeted again.
    void send_event(const std::string& name, const std::string& data);
    size_t event_clients() const;
    // A response is being written (a caller doing other work should come back to poll() soon).
    bool writing() const;
    uint64_t requests_served() const { return requests_; }

    // Accepts, reads and answers for at most `timeout` (returns sooner when nothing is pending
    // and the time has passed; never blocks longer than `timeout`).
    void poll(std::chrono::milliseconds timeout);

private:
    struct Client;
    void accept_clients();
    void read_from(Client& client);
    void write_to(Client& client);
    void answer(Client& client);
    bool host_allowed(const std::string& host) const;

    int listener_ = -1;
    uint16_t port_ = 0;
    std::string address_;
    bool loopback_ = true;
    HttpLimits limits_;
    std::vector<std::pair<std::string, Handler>> exact_, prefixes_;
    std::string events_path_;
    std::function<std::vector<std::pair<std::string, std::string>>()> greeting_;
    std::vector<std::unique_ptr<Client>> clients_;
    uint64_t requests_ = 0;
    std::chrono::steady_clock::time_point last_keepalive_;
};

}  // namespace ellicast::viewer
