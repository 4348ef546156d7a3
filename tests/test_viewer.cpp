// The live view's HTTP server (viewer/): routes, files kept inside their folder, the Host check
// against DNS rebinding, bounded requests, and the event stream with its greeting.
#include <ellicast/viewer/http_server.h>
#include <ellicast/viewer/web_assets.h>

#include <doctest/doctest.h>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

using namespace ellicast::viewer;

namespace {

// Sends `request` to the server on 127.0.0.1 and returns what comes back until the server closes
// the connection or `wait` passes, polling the server meanwhile (one thread).
std::string http_exchange(HttpServer& server, const std::string& request,
                          std::chrono::milliseconds wait = std::chrono::milliseconds(2000)) {
    int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(server.port());
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    fcntl(fd, F_SETFL, O_NONBLOCK);
    ::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
    std::string out;
    size_t sent = 0;
    const auto until = std::chrono::steady_clock::now() + wait;
    while (std::chrono::steady_clock::now() < until) {
        server.poll(std::chrono::milliseconds(5));
        if (sent < request.size()) {
            ssize_t n = ::send(fd, request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
            if (n > 0) sent += size_t(n);
        }
        char buffer[65536];
        ssize_t got = ::recv(fd, buffer, sizeof buffer, 0);
        if (got > 0) out.append(buffer, size_t(got));
        if (got == 0) break;
    }
    ::close(fd);
    return out;
}

std::string get(HttpServer& server, const std::string& path, const std::string& host = "127.0.0.1") {
    return http_exchange(server, "GET " + path + " HTTP/1.1\r\nHost: " + host + "\r\n\r\n");
}

}  // namespace

TEST_CASE("the live view's server answers its routes and refuses what would leave a served folder") {
    const auto dir = std::filesystem::temp_directory_path() / "ellicast-viewer-test";
    std::filesystem::create_directories(dir / "build");
    std::ofstream(dir / "build" / "three.module.js") << "export const x = 1;\n";
    std::ofstream(dir / ".hidden") << "secret\n";
    HttpServer server;
    std::string error;
    REQUIRE(server.listen("127.0.0.1", 0, error));
    CHECK(server.port() != 0);
    CHECK(server.loopback());
    server.route("/hello", [](const std::string&, const std::string& query) {
        HttpResponse r;
        r.body = "hello " + query;
        return r;
    });
    server.route_prefix("/three/", [&](const std::string& rest, const std::string&) { return file_response(dir, rest); });

    std::string r = get(server, "/hello?v=3");
    CHECK(r.rfind("HTTP/1.1 200 OK\r\n", 0) == 0);
    CHECK(r.find("\r\n\r\nhello v=3") != std::string::npos);
    r = get(server, "/three/build/three.module.js");
    CHECK(r.find("200 OK") != std::string::npos);
    CHECK(r.find("Content-Type: text/javascript") != std::string::npos);
    CHECK(r.find("export const x = 1;") != std::string::npos);
    CHECK(get(server, "/three/../three/build/three.module.js").find("403 Forbidden") != std::string::npos);
    CHECK(get(server, "/three/.hidden").find("403 Forbidden") != std::string::npos);
    CHECK(get(server, "/three//etc/passwd").find("403 Forbidden") != std::string::npos);
    CHECK(get(server, "/three/build").find("403 Forbidden") != std::string::npos);
    CHECK(get(server, "/three/nothing.js").find("404 Not Found") != std::string::npos);
    CHECK(get(server, "/elsewhere").find("404 Not Found") != std::string::npos);
    // Another site's name in Host while bound to loopback: a DNS-rebinding page, refused.
    CHECK(get(server, "/hello", "evil.example:8765").find("403 Forbidden") != std::string::npos);
    CHECK(get(server, "/hello", "localhost:8765").find("200 OK") != std::string::npos);
    CHECK(http_exchange(server, "POST /hello HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n").find("405") != std::string::npos);
    CHECK(http_exchange(server, "garbage\r\n\r\n").find("400 Bad Request") != std::string::npos);
    // Headers past the limit: refused, and the connection closed (nothing is held for it).
    CHECK(http_exchange(server, "GET /hello HTTP/1.1\r\nX: " + std::string(40000, 'a')).find("431") != std::string::npos);
    std::filesystem::remove_all(dir);
}

TEST_CASE("the live view's event stream greets a new page, then pushes events as they happen") {
    HttpServer server;
    std::string error;
    REQUIRE(server.listen("127.0.0.1", 0, error));
    server.event_stream("/events", [] {
        return std::vector<std::pair<std::string, std::string>>{{"status", "{\"n\":1}"}};
    });
    int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(server.port());
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    REQUIRE(::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0);
    const std::string request = "GET /events HTTP/1.1\r\nHost: localhost\r\n\r\n";
    REQUIRE(::send(fd, request.data(), request.size(), 0) == ssize_t(request.size()));
    fcntl(fd, F_SETFL, O_NONBLOCK);
    std::string got;
    auto read_for = [&](int ms) {
        const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
        while (std::chrono::steady_clock::now() < until) {
            server.poll(std::chrono::milliseconds(5));
            char buffer[4096];
            ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
            if (n > 0) got.append(buffer, size_t(n));
        }
    };
    read_for(200);
    CHECK(server.event_clients() == 1);
    CHECK(got.find("Content-Type: text/event-stream") != std::string::npos);
    CHECK(got.find("event: status\ndata: {\"n\":1}\n\n") != std::string::npos);
    // A newline in the data would end the event early: it goes as a space.
    server.send_event("model", "{\"version\":2,\n\"x\":1}");
    read_for(200);
    CHECK(got.find("event: model\ndata: {\"version\":2, \"x\":1}\n\n") != std::string::npos);
    ::close(fd);
    read_for(100);
    CHECK(server.event_clients() == 0);
}

TEST_CASE("the live view's page is compiled in: its HTML, script and style") {
    for (const char* name : {"index.html", "viewer.js", "viewer.css"}) {
        const WebAsset* asset = find_web_asset(name);
        REQUIRE_MESSAGE(asset, name);
        CHECK(asset->size > 100);
    }
    const WebAsset* page = find_web_asset("index.html");
    const std::string html(reinterpret_cast<const char*>(page->data), page->size);
    CHECK(html.find("/three/build/three.module.js") != std::string::npos);  // served locally, no CDN
    CHECK(html.find("https://") == std::string::npos);
    CHECK(find_web_asset("missing.js") == nullptr);
}
