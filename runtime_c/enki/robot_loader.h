/*
 * robot_loader.h - loads the robots' shared objects for the world runner
 * (world_runner.cpp): one copy per robot, the copies' code shared.
 *
 * dlopen loads a file once, and every robot needs its own globals (the
 * runtime's state is its globals), so each robot after the first of a
 * program loads its own copy of the program's file, written beside the
 * SPEC.  The copies' read-only segments (code, constants, symbol tables)
 * hold the same bytes as the first robot's, but at other pages: with 50
 * robots the processor's caches held 50 copies of the same code, and
 * fetching them cost a fifth of a run (docs/performance.md).  So the
 * read-only pages of each copy are mapped again from the first robot's
 * file, at the same addresses: the bytes stay the same, and the caches hold
 * one copy.  Only when they are the same: a segment is shared after its
 * loaded bytes compare equal to the first robot's and when no writable
 * segment shares its pages; otherwise the copy keeps its own (slower, as
 * exact).  Linux (dl_iterate_phdr, dlinfo); elsewhere the copies keep
 * their own pages.
 */
#ifndef ROBOT_LOADER_H
#define ROBOT_LOADER_H

#include <dlfcn.h>
#include <fcntl.h>
#include <unistd.h>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#if defined(__linux__)
#include <link.h>
#include <sys/mman.h>
#define ROBOT_LOADER_SHARES 1
#else
#define ROBOT_LOADER_SHARES 0
#endif

namespace loader {

// `from` copied to `to`; false when it cannot be.
inline bool copy_file(const std::string &from, const std::string &to)
{
    FILE *in = std::fopen(from.c_str(), "rb");
    if (in == nullptr)
        return false;
    FILE *out = std::fopen(to.c_str(), "wb");
    bool ok = out != nullptr;
    char buf[1 << 16];
    size_t n;
    while (ok && (n = std::fread(buf, 1, sizeof buf, in)) > 0)
        ok = std::fwrite(buf, 1, n, out) == n;
    ok = ok && !std::ferror(in);
    std::fclose(in);
    if (out != nullptr)
        ok = std::fclose(out) == 0 && ok;
    return ok;
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
                || std::memcmp((const void *)s.start, (const void *)t.start, s.length) != 0)
            continue;
        // MAP_FIXED replaces the copy's pages at once: the code that runs
        // here is the runner's, never the robot's
        (void)mmap((void *)t.start, t.length, t.prot, MAP_PRIVATE | MAP_FIXED, fd, s.offset);
    }
    close(fd);
}
#endif

// Loads `path` for a robot: the file itself for the first robot of that
// path (`first` null), else a copy at `copy_path` whose read-only pages are
// shared with `first`'s.  Null (and *error) when it cannot be loaded.
inline void *load(const std::string &path, void *first, const std::string &copy_path,
                  std::string *error)
{
    if (first == nullptr) {
        void *h = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (h == nullptr)
            *error = dlerror();
        return h;
    }
    if (!copy_file(path, copy_path)) {
        *error = "cannot copy " + path + " to " + copy_path;
        return nullptr;
    }
    void *h = dlopen(copy_path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (h == nullptr) {
        *error = dlerror();
        return nullptr;
    }
#if ROBOT_LOADER_SHARES
    share_pages(first, h, path);
#endif
    return h;
}

}  // namespace loader

#endif
