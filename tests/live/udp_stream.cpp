// udp_stream — records the UDP datagrams a simulator sends, with their arrival times, and sends
// such a recording again at its recorded timing, for `zenith live`'s tests (tests/data/live).
//
//   udp_stream record PORT SECONDS FILE [PORT2 FILE2]   datagrams arriving on 127.0.0.1:PORT
//   udp_stream send FILE HOST PORT [SCALE]              each datagram at its time / SCALE
//
// A recording is text: '#' comment lines, then one line per datagram, "<seconds since the
// first> <the bytes in hex>". Only loopback-or-given hosts; no name resolution.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

int Bind(int port) {
    const int fd = socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (fd < 0 || bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
        std::perror("udp_stream: bind");
        std::exit(1);
    }
    return fd;
}

int Record(const std::vector<std::pair<int, std::string>>& outputs, double seconds) {
    std::vector<pollfd> fds;
    std::vector<std::ofstream> files;
    for (const auto& [port, path] : outputs) {
        fds.push_back({Bind(port), POLLIN, 0});
        files.emplace_back(path);
        files.back() << "# udp_stream recording: 127.0.0.1:" << port
                     << "; <seconds since the first datagram> <bytes in hex>\n";
    }
    std::vector<double> first(outputs.size(), -1.0);
    std::vector<int> counts(outputs.size(), 0);
    const auto start = Clock::now();
    char buffer[65536];
    while (std::chrono::duration<double>(Clock::now() - start).count() < seconds) {
        if (poll(fds.data(), fds.size(), 100) <= 0) continue;
        const double now = std::chrono::duration<double>(Clock::now() - start).count();
        for (std::size_t i = 0; i < fds.size(); ++i) {
            if (!(fds[i].revents & POLLIN)) continue;
            const ssize_t n = recv(fds[i].fd, buffer, sizeof buffer, 0);
            if (n < 0) continue;
            if (first[i] < 0) first[i] = now;
            char stamp[32];
            std::snprintf(stamp, sizeof stamp, "%.6f ", now - first[i]);
            files[i] << stamp;
            for (ssize_t k = 0; k < n; ++k) {
                char hex[3];
                std::snprintf(hex, sizeof hex, "%02x", static_cast<unsigned char>(buffer[k]));
                files[i] << hex;
            }
            files[i] << '\n';
            ++counts[i];
        }
    }
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        std::cerr << "udp_stream: " << counts[i] << " datagrams from port " << outputs[i].first
                  << " into " << outputs[i].second << "\n";
    }
    return 0;
}

int Send(const std::string& path, const std::string& host, int port, double scale) {
    std::ifstream in(path);
    if (!in) {
        std::cerr << "udp_stream: cannot read " << path << "\n";
        return 1;
    }
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    if (inet_pton(AF_INET, host.c_str(), &address.sin_addr) != 1) {
        std::cerr << "udp_stream: host " << host << " is not an IPv4 address\n";
        return 1;
    }
    const int fd = socket(AF_INET, SOCK_DGRAM, 0);
    const auto start = Clock::now();
    std::string line;
    int sent = 0;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream fields(line);
        double t = 0.0;
        std::string hex;
        fields >> t >> hex;
        std::vector<unsigned char> bytes;
        for (std::size_t k = 0; k + 1 < hex.size(); k += 2) {
            bytes.push_back(static_cast<unsigned char>(std::stoul(hex.substr(k, 2), nullptr, 16)));
        }
        std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(
                                                  std::chrono::duration<double>(t / scale)));
        if (sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&address),
                   sizeof address) < 0) {
            std::perror("udp_stream: sendto");
        }
        ++sent;
    }
    std::cerr << "udp_stream: sent " << sent << " datagrams from " << path << "\n";
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const std::vector<std::string> args(argv + 1, argv + argc);
    if (args.size() >= 4 && args[0] == "record" && args.size() % 2 == 0) {
        std::vector<std::pair<int, std::string>> outputs;
        outputs.emplace_back(std::stoi(args[1]), args[3]);
        for (std::size_t i = 4; i + 1 < args.size(); i += 2) {
            outputs.emplace_back(std::stoi(args[i]), args[i + 1]);
        }
        return Record(outputs, std::stod(args[2]));
    }
    if ((args.size() == 4 || args.size() == 5) && args[0] == "send") {
        return Send(args[1], args[2], std::stoi(args[3]),
                    args.size() == 5 ? std::stod(args[4]) : 1.0);
    }
    std::cerr << "usage: udp_stream record PORT SECONDS FILE [PORT2 FILE2]\n"
                 "       udp_stream send FILE HOST PORT [SCALE]\n";
    return 2;
}
