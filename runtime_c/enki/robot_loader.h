/*
 * robot_loader.h - loads the robots' shared objects for the world runner
 * (world_runner.cpp): one object per program, each robot's own state
 * swapped into it while that robot's code runs.
 *
 * The runtime's state is its globals, and every robot needs its own.  The
 * robots of a program run one after the other (coroutines of one thread),
 * so they share one loaded copy of the program's file, and each robot keeps
 * its own copy of the object's writable data (.data and .bss: the pages
 * that are written after loading; state_of): the runner copies a robot's
 * bytes in before resuming it and out when it yields (world_runner.cpp,
 * swap_in and swap_out: some 4 KB each way for a rule program).  The code
 * then runs at the same addresses for every robot, and what the processor
 * keeps of code by its address (branch predictors, decoded instructions,
 * TLB entries) serves them all: with one copy of the file per robot (the
 * design before, its code pages shared as below), a poll took 4 times as
 * long with 50 robots as with one or two, and the whole run 12 % more
 * (docs/performance.md, "One object for all the robots of a program").
 *
 * Two kinds of program keep one copy of the file per robot instead: one
 * with thread-local storage (a PT_TLS segment: a user's C file with
 * _Thread_local), which is not in those pages (each loaded object has its
 * own TLS block), and one with more than MAX_SWAPPED_STATE bytes of state,
 * whose swapping would cost more than the copies do.  Each robot after the
 * first then loads its own copy of the file, a file in memory
 * (memfd_create) where Linux has them, else a file written beside the
 * SPEC, whose read-only segments are mapped again from the first robot's
 * file after their loaded bytes compare equal, so that the caches hold the
 * code once (only when no writable segment shares their pages).  Linux
 * (dl_iterate_phdr, dlinfo); elsewhere the copies keep their own pages.
 */
#ifndef ROBOT_LOADER_H
#define ROBOT_LOADER_H

#include <dlfcn.h>
#include <fcntl.h>
#include <unistd.h>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <link.h>
#include <sys/mman.h>
#define ROBOT_LOADER_SHARES 1
#else
#define ROBOT_LOADER_SHARES 0
#endif

// Under AddressSanitizer an object's segments hold the redzones it puts
// around each global, which no instrumented access may touch: a robot's
// state is copied whole, redzones too (their bytes are never written, and
// their shadow, which is not copied, is the same for every robot of the
// object), and the read-only pages of copies compared whole, by a copy and
// a comparison ASan does not check.
#if defined(__SANITIZE_ADDRESS__)
#define ROBOT_LOADER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ROBOT_LOADER_ASAN 1
#endif
#endif

namespace loader {

#if defined(ROBOT_LOADER_ASAN)
// (byte by byte through volatile pointers: never turned into a call of
// memcpy, which ASan intercepts and checks)
__attribute__((no_sanitize_address)) inline void copy_state(void *to, const void *from,
                                                             size_t n)
{
    volatile unsigned char *t = static_cast<volatile unsigned char *>(to);
    const volatile unsigned char *f = static_cast<const volatile unsigned char *>(from);
    for (size_t i = 0; i < n; i++)
        t[i] = f[i];
}

__attribute__((no_sanitize_address)) inline bool same_bytes(const void *a, const void *b,
                                                             size_t n)
{
    const volatile unsigned char *x = static_cast<const volatile unsigned char *>(a);
    const volatile unsigned char *y = static_cast<const volatile unsigned char *>(b);
    for (size_t i = 0; i < n; i++)
        if (x[i] != y[i])
            return false;
    return true;
}
#else
inline void copy_state(void *to, const void *from, size_t n)
{
    std::memcpy(to, from, n);
}

inline bool same_bytes(const void *a, const void *b, size_t n)
{
    return std::memcmp(a, b, n) == 0;
}
#endif

// The bytes of `path` (read once for all its robots); false when it cannot be read.
inline bool file_bytes(const std::string &path, const std::string **bytes)
{
    static std::map<std::string, std::string> read;
    auto found = read.find(path);
    if (found == read.end()) {
        FILE *in = std::fopen(path.c_str(), "rb");
        if (in == nullptr)
            return false;
        std::string data;
        char buf[1 << 16];
        size_t n;
        while ((n = std::fread(buf, 1, sizeof buf, in)) > 0)
            data.append(buf, n);
        bool ok = !std::ferror(in);
        std::fclose(in);
        if (!ok)
            return false;
        found = read.emplace(path, std::move(data)).first;
    }
    *bytes = &found->second;
    return true;
}

inline bool write_all(int fd, const std::string &data)
{
    size_t done = 0;
    while (done < data.size()) {
        ssize_t n = write(fd, data.data() + done, data.size() - done);
        if (n <= 0)
            return false;
        done += (size_t)n;
    }
    return true;
}

// The memory files of the copies: open until every robot is loaded, since
// the dynamic loader knows a loaded object by its path too, and a memory
// file's path is its descriptor's number, which a closed one gives back.
inline std::vector<int> &memory_files()
{
    static std::vector<int> fds;
    return fds;
}

// A copy of `path` to dlopen: a memory file where there are, else a file
// at `file_path`; its path, or "" when it cannot be made.
inline std::string copy_of(const std::string &path, const std::string &file_path)
{
    const std::string *bytes;
    if (!file_bytes(path, &bytes))
        return "";
#if defined(__linux__) && defined(MFD_CLOEXEC)
    int fd = memfd_create("epuck-robot", MFD_CLOEXEC);
    if (fd >= 0) {
        if (write_all(fd, *bytes)) {
            memory_files().push_back(fd);
            return "/proc/self/fd/" + std::to_string(fd);
        }
        close(fd);
    }
#endif
    int out = open(file_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (out < 0)
        return "";
    bool ok = write_all(out, *bytes);
    return close(out) == 0 && ok ? file_path : "";
}

#if ROBOT_LOADER_SHARES
struct Segment {
    uintptr_t start;        // page-aligned, in memory
    size_t length;          // whole pages
    off_t offset;           // of `start` in the file
    int prot;
};

struct Found {
    ElfW(Addr) base;
    std::vector<Segment> read_only;
    bool overlap;           // a writable segment shares a read-only page
};

inline int find_segments(struct dl_phdr_info *info, size_t, void *data)
{
    Found *f = static_cast<Found *>(data);
    if (info->dlpi_addr != f->base)
        return 0;
    uintptr_t page = (uintptr_t)sysconf(_SC_PAGESIZE);
    std::vector<std::pair<uintptr_t, uintptr_t>> writable;
    for (int i = 0; i < info->dlpi_phnum; i++) {
        const ElfW(Phdr) &ph = info->dlpi_phdr[i];
        if (ph.p_type != PT_LOAD)
            continue;
        uintptr_t a = info->dlpi_addr + ph.p_vaddr;
        uintptr_t start = a & ~(page - 1);
        uintptr_t end = (a + ph.p_memsz + page - 1) & ~(page - 1);
        if (ph.p_flags & PF_W) {
            writable.push_back({start, end});
        } else if (ph.p_filesz == ph.p_memsz) {
            int prot = PROT_READ | ((ph.p_flags & PF_X) ? PROT_EXEC : 0);
            f->read_only.push_back({start, end - start, (off_t)(ph.p_offset - (a - start)), prot});
        }
    }
    for (const Segment &s : f->read_only)
        for (const auto &w : writable)
            if (w.first < s.start + s.length && s.start < w.second)
                f->overlap = true;
    return 1;
}

inline Found segments_of(void *handle)
{
    Found f{0, {}, false};
    struct link_map *map = nullptr;
    if (dlinfo(handle, RTLD_DI_LINKMAP, &map) != 0 || map == nullptr)
        return Found{0, {}, true};
    f.base = map->l_addr;
    dl_iterate_phdr(find_segments, &f);
    return f;
}

// The copy's read-only pages mapped from the first robot's file (`path`),
// where they hold the same bytes as the first robot's loaded pages.
inline void share_pages(void *first, void *copy, const std::string &path)
{
    Found a = segments_of(first), b = segments_of(copy);
    if (a.overlap || b.overlap || a.read_only.size() != b.read_only.size())
        return;
    int fd = open(path.c_str(), O_RDONLY);
    if (fd < 0)
        return;
    for (size_t i = 0; i < a.read_only.size(); i++) {
        const Segment &s = a.read_only[i], &t = b.read_only[i];
        if (s.length != t.length || s.offset != t.offset || s.prot != t.prot
                || !same_bytes((const void *)s.start, (const void *)t.start, s.length))
            continue;
        // MAP_FIXED replaces the copy's pages at once: the code that runs
        // here is the runner's, never the robot's
        (void)mmap((void *)t.start, t.length, t.prot, MAP_PRIVATE | MAP_FIXED, fd, s.offset);
    }
    close(fd);
}
#endif

// Swapping more bytes than this at every step costs more than the robots'
// copies of the file do: bench/world_bench.py's 50 robots swapping 6, 14
// and 30 KB more than wander's 9 KB of state ran 0.71, 0.80 and 1.06 times
// as long as the copies (docs/performance.md, "The robots' state grew"):
// the robots of an object with more state load their copies.
const size_t MAX_SWAPPED_STATE = 16384;

// The state a robot keeps of a loaded object: its writable pages that are
// not made read-only after relocation (PT_GNU_RELRO), in address order;
// `tls`: the object has thread-local storage, which is not in them;
// `swappable`: the robots of the object can share it (no TLS, at most
// MAX_SWAPPED_STATE bytes).
struct State {
    std::vector<std::pair<unsigned char *, size_t>> ranges;
    size_t size = 0;
    bool tls = false;
    bool swappable = false;
    uintptr_t base = 0;
};

#if ROBOT_LOADER_SHARES
inline int find_state(struct dl_phdr_info *info, size_t, void *data)
{
    State *s = static_cast<State *>(data);
    if (info->dlpi_addr != s->base)
        return 0;
    uintptr_t relro_start = 0, relro_end = 0;
    for (int i = 0; i < info->dlpi_phnum; i++) {
        const ElfW(Phdr) &ph = info->dlpi_phdr[i];
        if (ph.p_type == PT_TLS)
            s->tls = true;
        if (ph.p_type == PT_GNU_RELRO) {
            relro_start = info->dlpi_addr + ph.p_vaddr;
            relro_end = relro_start + ph.p_memsz;
        }
    }
    for (int i = 0; i < info->dlpi_phnum; i++) {
        const ElfW(Phdr) &ph = info->dlpi_phdr[i];
        if (ph.p_type != PT_LOAD || !(ph.p_flags & PF_W))
            continue;
        uintptr_t start = info->dlpi_addr + ph.p_vaddr, end = start + ph.p_memsz;
        // RELRO is at the start of its segment (the linker puts it there)
        if (relro_start <= start && start < relro_end)
            start = relro_end < end ? relro_end : end;
        if (start < end) {
            s->ranges.push_back({reinterpret_cast<unsigned char *>(start), end - start});
            s->size += end - start;
        }
    }
    return 1;
}

#endif

// The state of a loaded object (not swappable where it cannot be found:
// elsewhere than on Linux, each robot loads its copy).
inline State state_of(void *handle)
{
    State s;
#if ROBOT_LOADER_SHARES
    struct link_map *map = nullptr;
    if (dlinfo(handle, RTLD_DI_LINKMAP, &map) != 0 || map == nullptr)
        return s;
    s.base = map->l_addr;
    dl_iterate_phdr(find_state, &s);
#else
    (void)handle;
#endif
    s.swappable = !s.tls && !s.ranges.empty() && s.size <= MAX_SWAPPED_STATE;
    return s;
}

// A robot's own copy of the state of the object it shares with other
// robots: into the object's data pages before the robot's code runs, out
// of them when it has yielded (some 4 KB each way for a rule program: as
// long as a poll of a robot alone, docs/performance.md).  Inert for a robot
// that has its object alone.
struct Swapped {
    const State *of = nullptr;
    std::vector<unsigned char> bytes;

    // the object's state as it is now (loaded, its constructors run) is
    // this robot's start
    void share(const State &state)
    {
        of = &state;
        bytes.resize(state.size);
        swap_out();
    }

    void swap_in() const
    {
        if (of == nullptr)
            return;
        const unsigned char *from = bytes.data();
        for (const auto &range : of->ranges) {
            copy_state(range.first, from, range.second);
            from += range.second;
        }
    }

    void swap_out()
    {
        if (of == nullptr)
            return;
        unsigned char *to = bytes.data();
        for (const auto &range : of->ranges) {
            copy_state(to, range.first, range.second);
            to += range.second;
        }
    }

    // Asks the processor for this robot's copy ahead of its swap_in.
    void prefetch() const
    {
        for (size_t i = 0; i < bytes.size(); i += BLOCK)
            __builtin_prefetch(bytes.data() + i);
    }

private:
    static const size_t BLOCK = 64;
};

// Loads `path` for a robot: the file itself for the first robot of that
// path (`first` null), else a copy (in memory, or at `copy_path`) whose
// read-only pages are shared with `first`'s.  Null (and *error) when it
// cannot be loaded.
inline void *load(const std::string &path, void *first, const std::string &copy_path,
                  std::string *error)
{
    if (first == nullptr) {
        void *h = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (h == nullptr)
            *error = dlerror();
        return h;
    }
    std::string copy = copy_of(path, copy_path);
    if (copy.empty()) {
        *error = "cannot copy " + path + " to " + copy_path;
        return nullptr;
    }
    void *h = dlopen(copy.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (h == nullptr) {
        *error = dlerror();
        return nullptr;
    }
#if ROBOT_LOADER_SHARES
    share_pages(first, h, path);
#endif
    return h;
}

// Every robot is loaded: the memory files' descriptors are closed (the
// mappings keep the files).
inline void loaded()
{
    for (int fd : memory_files())
        close(fd);
    memory_files().clear();
}

}  // namespace loader

#endif
