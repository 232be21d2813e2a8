// Bytes of a GL buffer carried to the CPU without waiting for the GPU: each Copy goes into one of
// kSlots parts of a persistently mapped buffer behind a fence; Latest takes the newest part whose
// fence has signalled. A copy still pending when its part comes round again is dropped. For
// what a host reads every frame and may have a frame or two late (the clouds' shade, the
// environment's spherical harmonics).
#pragma once

#include <glad/gl.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace zenith::sky::gl {

class FencedReadback {
  public:
    static constexpr std::size_t kSlots = 3;

    explicit FencedReadback(std::size_t bytes) : bytes_(bytes) {
        constexpr GLbitfield flags = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
        const auto size = static_cast<GLsizeiptr>(kSlots * bytes_);
        glCreateBuffers(1, &buffer_);
        glNamedBufferStorage(buffer_, size, nullptr, flags);
        mapped_ = static_cast<const unsigned char*>(glMapNamedBufferRange(buffer_, 0, size, flags));
    }
    ~FencedReadback() {
        for (GLsync& fence : fences_) {
            if (fence != nullptr) glDeleteSync(fence);
        }
        glUnmapNamedBuffer(buffer_);
        glDeleteBuffers(1, &buffer_);
    }
    FencedReadback(const FencedReadback&) = delete;
    FencedReadback& operator=(const FencedReadback&) = delete;

    // The first `bytes` of `source`, which a shader wrote.
    void Copy(GLuint source) {
        Poll();
        const std::size_t slot = next_;
        next_ = (next_ + 1) % kSlots;
        if (fences_[slot] != nullptr) glDeleteSync(fences_[slot]);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glCopyNamedBufferSubData(source, buffer_, 0, static_cast<GLintptr>(slot * bytes_),
                                 static_cast<GLsizeiptr>(bytes_));
        glMemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
        fences_[slot] = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
        serial_[slot] = ++copies_;
    }

    // The newest finished copy, or nullptr before the first has arrived; valid until the next
    // call.
    const unsigned char* Latest() {
        Poll();
        return latest_.empty() ? nullptr : latest_.data();
    }

  private:
    void Poll() {
        for (std::size_t slot = 0; slot < kSlots; ++slot) {
            if (fences_[slot] == nullptr) continue;
            // Flushing (not waiting) so that the fence can signal without a later frame's flush.
            const GLenum state = glClientWaitSync(fences_[slot], GL_SYNC_FLUSH_COMMANDS_BIT, 0);
            if (state != GL_ALREADY_SIGNALED && state != GL_CONDITION_SATISFIED) continue;
            glDeleteSync(fences_[slot]);
            fences_[slot] = nullptr;
            if (serial_[slot] < latest_serial_) continue;
            latest_.assign(mapped_ + slot * bytes_, mapped_ + (slot + 1) * bytes_);
            latest_serial_ = serial_[slot];
        }
    }

    std::size_t bytes_;
    GLuint buffer_ = 0;
    const unsigned char* mapped_ = nullptr;
    std::array<GLsync, kSlots> fences_{};
    std::array<std::uint64_t, kSlots> serial_{};
    std::uint64_t copies_ = 0, latest_serial_ = 0;
    std::size_t next_ = 0;
    std::vector<unsigned char> latest_;
};

}  // namespace zenith::sky::gl
