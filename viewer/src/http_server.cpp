// The live view's HTTP server (see http_server.h).
#include <ellicast/viewer/http_server.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

namespace ellicast::viewer {

struct HttpServer::Client {
    int fd = -1;
    std::string in;
    std::string out;
    size_t sent = 0;
    bool events = false;      // an open event stream
    bool close_after = false; // close once `out` is written
    std::chrono::steady_clock::time_point opened;
    ~Client() {
        if (fd >= 0) ::close(fd);
    }
};

namespace {

const char* reason_phrase(int status) {
    switch (status) {
        case 200: return "OK";
        case 400: return "Bad Request";
        case 403: return "Forbidden";
        case 404: return "Not Found";
        case 405: return "Method Not Allowed";
        case 413: return "Payload Too Large";
        case 431: return "Request Header Fields Too Large";
        case 500: return "Internal Server Error";
        case 503: return "Service Unavailable";
        default: return "Error";
    }
}

std::string response_bytes(const HttpResponse& r, bool head) {
    std::ostringstream s;
    s << "HTTP/1.1 " << r.status << ' ' << reason_phrase(r.status) << "\r\n"
      << "Content-Type: " << r.content_type << "\r\n"
      << "Content-Length: " << r.body.size() << "\r\n"
      << "X-Content-Type-Options: nosniff\r\n"
      << (r.no_store ? "Cache-Control: no-store\r\n" : "Cache-Control: max-age=60\r\n")
      << "Connection: close\r\n\r\n";
    std::string bytes = s.str();
    if (!head) bytes += r.body;
    return bytes;
}

std::string event_bytes(const std::string& name, const std::string& data) {
    // Data is one line: a newline in it would end the event early.
    std::string line = data;
    std::replace(line.begin(), line.end(), '\n', ' ');
    std::replace(line.begin(), line.end(), '\r', ' ');
    return "event: " + name + "\ndata: " + line + "\n\n";
}

bool set_nonblocking(int fd) {
    int flags = fcntl(fd, F_GETFL, 0);
    return flags >= 0 && fcntl(fd, F_SETFL, flags | O_NONBLOCK) == 0;
}

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

}  // namespace

HttpResponse http_error(int status, const std::string& message) {
    HttpResponse r;
    r.status = status;
    r.body = message + "\n";
    r.no_store = true;
    return r;
}

std::string content_type_for(const std::string& name) {
    auto ends = [&](const char* ext) {
        size_t n = std::strlen(ext);
        return name.size() >= n && lower(name.substr(name.size() - n)) == ext;
    };
    if (ends(".html")) return "text/html; charset=utf-8";
    if (ends(".js") || ends(".mjs")) return "text/javascript; charset=utf-8";
    if (ends(".css")) return "text/css; charset=utf-8";
    if (ends(".json")) return "application/json";
    if (ends(".glb")) return "model/gltf-binary";
    if (ends(".png")) return "image/png";
    if (ends(".svg")) return "image/svg+xml";
    if (ends(".wasm")) return "application/wasm";
    return "application/octet-stream";
}

HttpResponse file_response(const std::filesystem::path& root, const std::string& relative, size_t max_bytes) {
    if (relative.empty()) return http_error(404, "not found");
    if (relative.front() == '/') return http_error(403, "forbidden: absolute path");
    std::stringstream parts(relative);
    std::string part;
    while (std::getline(parts, part, '/')) {
        if (part.empty() || part[0] == '.') return http_error(403, "forbidden: path component \"" + part + "\"");
        for (unsigned char c : part)
            if (c < 0x20 || c == 0x7F || c == '\\') return http_error(403, "forbidden: character in path");
    }
    std::error_code ec;
    const std::filesystem::path file = root / relative;
    if (!std::filesystem::exists(file, ec)) return http_error(404, "not found: " + relative);
    if (!std::filesystem::is_regular_file(file, ec)) return http_error(403, "forbidden: not a file");
    const auto size = std::filesystem::file_size(file, ec);
    if (ec) return http_error(404, "not found: " + relative);
    if (size > max_bytes) return http_error(413, "file too large: " + relative);
    std::ifstream in(file, std::ios::binary);
    HttpResponse r;
    r.content_type = content_type_for(relative);
    r.body.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (!in && !in.eof()) return http_error(500, "cannot read " + relative);
    return r;
}

HttpServer::HttpServer() = default;

HttpServer::~HttpServer() {
    clients_.clear();
    if (listener_ >= 0) ::close(listener_);
}

bool HttpServer::listen(const std::string& address, uint16_t port, std::string& error, HttpLimits limits) {
    limits_ = limits;
    const std::string host = address == "localhost" ? "127.0.0.1" : address;
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_flags = AI_NUMERICHOST | AI_PASSIVE;
    addrinfo* found = nullptr;
    const std::string port_text = std::to_string(port);
    if (int rc = getaddrinfo(host.c_str(), port_text.c_str(), &hints, &found); rc != 0) {
        error = "\"" + address + "\" is not an IP address to listen on (" + gai_strerror(rc) + ")";
        return false;
    }
    std::unique_ptr<addrinfo, decltype(&freeaddrinfo)> holder(found, freeaddrinfo);
    int fd = ::socket(found->ai_family, SOCK_STREAM, 0);
    if (fd < 0) {
        error = std::string("cannot open a socket: ") + std::strerror(errno);
        return false;
    }
    int one = 1;
    setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    if (::bind(fd, found->ai_addr, found->ai_addrlen) != 0 || ::listen(fd, 32) != 0 || !set_nonblocking(fd)) {
        error = "cannot listen on " + address + ":" + port_text + ": " + std::strerror(errno);
        ::close(fd);
        return false;
    }
    sockaddr_storage bound{};
    socklen_t length = sizeof bound;
    getsockname(fd, reinterpret_cast<sockaddr*>(&bound), &length);
    if (bound.ss_family == AF_INET) {
        const auto* a = reinterpret_cast<const sockaddr_in*>(&bound);
        port_ = ntohs(a->sin_port);
        loopback_ = (ntohl(a->sin_addr.s_addr) >> 24) == 127;
    } else {
        const auto* a = reinterpret_cast<const sockaddr_in6*>(&bound);
        port_ = ntohs(a->sin6_port);
        loopback_ = IN6_IS_ADDR_LOOPBACK(&a->sin6_addr);
    }
    address_ = host;
    listener_ = fd;
    last_keepalive_ = std::chrono::steady_clock::now();
    return true;
}

std::string HttpServer::url() const {
    std::string host = address_;
    if (host == "0.0.0.0") host = "127.0.0.1";
    if (host == "::") host = "::1";
    if (host.find(':') != std::string::npos) host = "[" + host + "]";
    return "http://" + host + ":" + std::to_string(port_) + "/";
}

void HttpServer::route(const std::string& path, Handler handler) { exact_.emplace_back(path, std::move(handler)); }

void HttpServer::route_prefix(const std::string& prefix, Handler handler) {
    prefixes_.emplace_back(prefix, std::move(handler));
}

void HttpServer::event_stream(const std::string& path,
                              std::function<std::vector<std::pair<std::string, std::string>>()> greeting) {
    events_path_ = path;
    greeting_ = std::move(greeting);
}

size_t HttpServer::event_clients() const {
    return static_cast<size_t>(std::count_if(clients_.begin(), clients_.end(), [](const auto& c) { return c->events; }));
}

bool HttpServer::writing() const {
    return std::any_of(clients_.begin(), clients_.end(),
                       [](const auto& c) { return c->fd >= 0 && !c->events && c->sent < c->out.size(); });
}

void HttpServer::send_event(const std::string& name, const std::string& data) {
    const std::string bytes = event_bytes(name, data);
    for (auto& c : clients_) {
        if (!c->events || c->fd < 0) continue;
        if (c->out.size() - c->sent + bytes.size() > limits_.max_event_backlog) {
            ::close(c->fd);  // too slow: dropped; the page reconnects
            c->fd = -1;
            continue;
        }
        c->out += bytes;
        write_to(*c);
    }
}

bool HttpServer::host_allowed(const std::string& host_header) const {
    if (!loopback_) return true;
    std::string host = lower(host_header);
    // Strip the port: "[::1]:8765", "127.0.0.1:8765", "localhost".
    if (!host.empty() && host[0] == '[') {
        auto close = host.find(']');
        host = close == std::string::npos ? host : host.substr(1, close - 1);
    } else if (auto colon = host.rfind(':'); colon != std::string::npos) {
        host = host.substr(0, colon);
    }
    return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

void HttpServer::accept_clients() {
    for (;;) {
        int fd = ::accept(listener_, nullptr, nullptr);
        if (fd < 0) return;
        if (clients_.size() >= limits_.max_clients || !set_nonblocking(fd)) {
            ::close(fd);
            continue;
        }
        auto c = std::make_unique<Client>();
        c->fd = fd;
        c->opened = std::chrono::steady_clock::now();
        clients_.push_back(std::move(c));
    }
}

void HttpServer::read_from(Client& c) {
    char buffer[4096];
    for (;;) {
        ssize_t got = ::recv(c.fd, buffer, sizeof buffer, 0);
        if (got == 0 || (got < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
            ::close(c.fd);
            c.fd = -1;
            return;
        }
        if (got < 0) return;
        if (c.events || c.close_after) continue;  // nothing more is read from a client being answered
        c.in.append(buffer, static_cast<size_t>(got));
        if (c.in.find("\r\n\r\n") != std::string::npos || c.in.find("\n\n") != std::string::npos) {
            answer(c);
            return;
        }
        if (c.in.size() > limits_.max_request_bytes) {
            c.out = response_bytes(http_error(431, "request headers too large"), false);
            c.close_after = true;
            c.in.clear();
            return;
        }
    }
}

void HttpServer::answer(Client& c) {
    ++requests_;
    std::istringstream request(c.in);
    std::string line;
    std::getline(request, line);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream first(line);
    std::string method, target, version;
    first >> method >> target >> version;
    std::string host;
    while (std::getline(request, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty()) break;
        auto colon = line.find(':');
        if (colon != std::string::npos && lower(line.substr(0, colon)) == "host") {
            host = line.substr(colon + 1);
            host.erase(0, host.find_first_not_of(" \t"));
        }
    }
    c.in.clear();
    c.close_after = true;
    const bool head = method == "HEAD";
    HttpResponse r;
    if (target.empty() || target[0] != '/' || version.rfind("HTTP/1.", 0) != 0) {
        r = http_error(400, "bad request line");
    } else if (method != "GET" && !head) {
        r = http_error(405, "only GET and HEAD are served");
    } else if (!host_allowed(host)) {
        r = http_error(403, "this server answers only requests for localhost (Host: " + host + ")");
    } else {
        std::string path = target, query;
        if (auto q = target.find('?'); q != std::string::npos) {
            path = target.substr(0, q);
            query = target.substr(q + 1);
        }
        if (!events_path_.empty() && path == events_path_ && !head) {
            c.events = true;
            c.close_after = false;
            c.out = "HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\nCache-Control: no-store\r\n"
                    "X-Accel-Buffering: no\r\nConnection: keep-alive\r\n\r\nretry: 1000\n\n";
            if (greeting_)
                for (const auto& [name, data] : greeting_()) c.out += event_bytes(name, data);
            return;
        }
        bool found = false;
        for (const auto& [p, handler] : exact_)
            if (p == path) {
                r = handler(path, query);
                found = true;
                break;
            }
        if (!found)
            for (const auto& [p, handler] : prefixes_)
                if (path.rfind(p, 0) == 0) {
                    r = handler(path.substr(p.size()), query);
                    found = true;
                    break;
                }
        if (!found) r = http_error(404, "not found: " + path);
    }
    c.out = response_bytes(r, head);
    c.sent = 0;
}

void HttpServer::write_to(Client& c) {
    while (c.fd >= 0 && c.sent < c.out.size()) {
        ssize_t n = ::send(c.fd, c.out.data() + c.sent, c.out.size() - c.sent, MSG_NOSIGNAL);
        if (n < 0) {
            if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) return;
            ::close(c.fd);
            c.fd = -1;
            return;
        }
        c.sent += static_cast<size_t>(n);
    }
    if (c.sent >= c.out.size()) {
        c.out.clear();
        c.sent = 0;
        if (c.close_after && c.fd >= 0) {
            ::shutdown(c.fd, SHUT_WR);
            ::close(c.fd);
            c.fd = -1;
        }
    } else if (c.sent > (1 << 20)) {
        c.out.erase(0, c.sent);
        c.sent = 0;
    }
}

void HttpServer::poll(std::chrono::milliseconds timeout) {
    if (listener_ < 0) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_keepalive_ > std::chrono::seconds(15)) {
        last_keepalive_ = now;
        for (auto& c : clients_)
            if (c->events && c->fd >= 0) {
                c->out += ":\n\n";  // a comment keeps proxies and browsers from timing out
                write_to(*c);
            }
    }
    std::vector<pollfd> fds;
    fds.push_back({listener_, POLLIN, 0});
    for (auto& c : clients_) {
        short events = POLLIN;
        if (c->sent < c->out.size()) events |= POLLOUT;
        fds.push_back({c->fd, events, 0});
    }
    int ready = ::poll(fds.data(), fds.size(), static_cast<int>(std::max<int64_t>(0, timeout.count())));
    if (ready > 0) {
        if (fds[0].revents & POLLIN) accept_clients();
        for (size_t i = 1; i < fds.size() && i - 1 < clients_.size(); ++i) {
            Client& c = *clients_[i - 1];
            if (c.fd < 0) continue;
            if (fds[i].revents & (POLLERR | POLLNVAL)) {
                ::close(c.fd);
                c.fd = -1;
                continue;
            }
            if (fds[i].revents & (POLLIN | POLLHUP)) read_from(c);
            if (c.fd >= 0 && (fds[i].revents & POLLOUT)) write_to(c);
            if (c.fd >= 0 && !c.out.empty() && c.sent == 0) write_to(c);
        }
    }
    // A client that has not sent a whole request in time is closed (a slow-loris).
    const auto later = std::chrono::steady_clock::now();
    for (auto& c : clients_)
        if (c->fd >= 0 && !c->events && c->out.empty() && later - c->opened > limits_.request_timeout) {
            ::close(c->fd);
            c->fd = -1;
        }
    clients_.erase(std::remove_if(clients_.begin(), clients_.end(), [](const auto& c) { return c->fd < 0; }),
                   clients_.end());
}

}  // namespace ellicast::viewer
