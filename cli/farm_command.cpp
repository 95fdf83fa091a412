#include "farm_command.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "atomic_file.h"
#include "errors.h"
#include "frame_paths.h"
#include "movie.h"
#include "render_plan.h"
#include "reporter.h"
#include "scene.h"

namespace globular {

namespace fs = std::filesystem;

namespace {

/// What `globular farm` records in DIR/farm/farm.toml: the shot's settings, so --status
/// and --resubmit need neither the options again nor the scene, and every job submitted.
struct FarmRecord {
    FarmSettings settings;
    std::string meshFormat = "ply";
    bool sheet = false, movie = false;
    struct Submission {
        std::string step, id;
        std::vector<int> tasks;  ///< array tasks; empty: all (or not an array)
    };
    std::vector<Submission> jobs;
};

fs::path recordPath(const fs::path& outDir) { return farmDir(outDir) / "farm.toml"; }

void writeRecord(const FarmRecord& r) {
    const FarmSettings& s = r.settings;
    toml::array overrides;
    for (const std::string& o : s.overrides) overrides.push_back(o);
    toml::array jobs;
    for (const auto& job : r.jobs) {
        toml::array tasks;
        for (int t : job.tasks) tasks.push_back(t);
        jobs.push_back(toml::table{{"step", job.step}, {"id", job.id}, {"tasks", tasks}});
    }
    toml::table t{{"program", s.program.string()},
                  {"scene", s.scene.string()},
                  {"out", s.outDir.string()},
                  {"overrides", overrides},
                  {"frames", s.frames},
                  {"chunk", s.chunk},
                  {"max_running", s.maxRunning},
                  {"partition", s.partition},
                  {"account", s.account},
                  {"time", s.timeLimit},
                  {"plan_after_surface", s.planAfterSurface},
                  {"mesh_format", r.meshFormat},
                  {"contact_sheet", r.sheet},
                  {"movie", r.movie},
                  {"job", jobs}};
    std::ostringstream text;
    text << "# globular farm: the shot's settings and every job submitted for it\n" << t << "\n";
    writeFileAtomically(recordPath(s.outDir), text.str());
}

FarmRecord readRecord(const fs::path& outDir) {
    const fs::path path = recordPath(outDir);
    if (!fs::exists(path)) {
        throw IoError("farm: " + path.string() + " is missing: " + outDir.string() +
                      " was not submitted with `globular farm SCENE --out " + outDir.string() +
                      "`");
    }
    toml::table t;
    try {
        t = toml::parse_file(path.string());
    } catch (const toml::parse_error& e) {
        throw IoError("farm: " + path.string() + " is not TOML: " + std::string(e.description()));
    }
    const auto text = [&](const char* key) {
        const auto v = t[key].value<std::string>();
        if (!v) throw IoError("farm: " + path.string() + ": key '" + key + "' is missing");
        return *v;
    };
    const auto number = [&](const char* key) {
        const auto v = t[key].value<int64_t>();
        if (!v) throw IoError("farm: " + path.string() + ": key '" + key + "' is missing");
        return int(*v);
    };
    FarmRecord r;
    FarmSettings& s = r.settings;
    s.program = text("program");
    s.scene = text("scene");
    s.outDir = text("out");
    if (const toml::array* a = t["overrides"].as_array()) {
        for (const auto& o : *a) s.overrides.push_back(o.value<std::string>().value_or(""));
    }
    s.frames = number("frames");
    s.chunk = number("chunk");
    s.maxRunning = number("max_running");
    s.partition = text("partition");
    s.account = text("account");
    s.timeLimit = text("time");
    s.planAfterSurface = t["plan_after_surface"].value_or(false);
    r.meshFormat = text("mesh_format");
    r.sheet = t["contact_sheet"].value_or(false);
    r.movie = t["movie"].value_or(false);
    if (const toml::array* jobs = t["job"].as_array()) {
        for (const auto& node : *jobs) {
            const toml::table* job = node.as_table();
            if (!job) continue;
            FarmRecord::Submission sub{(*job)["step"].value_or(std::string()),
                                       (*job)["id"].value_or(std::string()),
                                       {}};
            if (const toml::array* tasks = (*job)["tasks"].as_array()) {
                for (const auto& k : *tasks) sub.tasks.push_back(int(k.value_or(int64_t(0))));
            }
            r.jobs.push_back(sub);
        }
    }
    s.validate();
    return r;
}

std::string commandLine(const std::string& program, const std::vector<std::string>& args) {
    std::string line = program;
    for (const std::string& a : args) line += " " + shellQuote(a);
    return line;
}

/// Runs a Slurm command. @throw Error naming it, its exit status and what it printed.
std::string slurm(const std::string& program, const std::vector<std::string>& args) {
    const ProgramResult r = runProgram(program, args);
    if (r.status != 0) {
        std::string answer = r.err.empty() ? r.out : r.err;
        while (!answer.empty() && (answer.back() == '\n' || answer.back() == ' ')) answer.pop_back();
        throw Error("farm: `" + commandLine(program, args) + "` failed with exit status " +
                    std::to_string(r.status) + ": " +
                    (answer.empty() ? "(it printed nothing)" : quoteForMessage(answer, 2000)));
    }
    return r.out;
}

/// sbatch --parsable prints "id" or "id;cluster".
std::string submit(const fs::path& script) {
    std::string out = slurm("sbatch", {"--parsable", script.string()});
    out = out.substr(0, out.find_first_of(";\n"));
    if (out.empty() || out.find_first_not_of("0123456789") != std::string::npos) {
        throw Error("farm: `sbatch --parsable " + script.string() +
                    "` answered no job id: " + quoteForMessage(out));
    }
    return out;
}

bool allExist(int first, int last, const auto& pathOf) {
    for (int f = first; f <= last; ++f) {
        if (!fs::exists(pathOf(f))) return false;
    }
    return true;
}

bool surfaceDone(const FarmRecord& r, int first, int last) {
    const fs::path& dir = r.settings.outDir;
    return allExist(first, last, [&](int f) { return surfaceVdbPath(dir, f); }) &&
           (!r.settings.planAfterSurface ||
            allExist(first, last, [&](int f) { return meshPath(dir, f, r.meshFormat); }));
}

bool renderDone(const FarmRecord& r, int first, int last) {
    return allExist(first, last, [&](int f) { return framePngPath(r.settings.outDir, f); });
}

bool finishDone(const FarmRecord& r) {
    const fs::path& dir = r.settings.outDir;
    return (!r.sheet || fs::exists(dir / "contact_sheet.png")) &&
           (!r.movie || fs::exists(dir / "movie.mp4"));
}

/// Writes the scripts of @p steps and submits them in order, each depending on those
/// before it that are submitted too. @p tasks: the array tasks of surface and render.
void submitSteps(FarmRecord& record, const std::set<std::string>& steps,
                 const std::map<std::string, std::vector<int>>& tasks, std::ostream& out) {
    const FarmSettings& s = record.settings;
    fs::create_directories(farmDir(s.outDir) / "logs");
    std::vector<std::string> ids(kFarmSteps.size());
    for (std::size_t k = 0; k < kFarmSteps.size(); ++k) {
        const std::string& step = kFarmSteps[k];
        if (!steps.count(step)) continue;
        const auto found = tasks.find(step);
        const std::vector<int> stepTasks = found == tasks.end() ? std::vector<int>{} : found->second;
        std::string dependency = farmDependency(s, step, ids);
        // aftercorr pairs task k with task k: only when both arrays hold the same tasks.
        if (step == "render" && tasks.count("surface") && tasks.at("surface") != stepTasks) {
            for (std::size_t at; (at = dependency.find("aftercorr:")) != std::string::npos;)
                dependency.replace(at, 10, "afterok:");
        }
        const fs::path script = farmDir(s.outDir) / (step + ".sbatch");
        writeFileAtomically(script, farmScript(s, step, dependency, stepTasks));
        ids[k] = submit(script);
        record.jobs.push_back({step, ids[k], stepTasks});
        out << "submitted " << step << ": job " << ids[k];
        if (step == "surface" || step == "render") out << " (array " << farmArraySpec(s, stepTasks) << ")";
        if (!dependency.empty()) out << ", after " << dependency;
        out << "\n";
        writeRecord(record);  // after each job, so a failure later leaves the ids known
    }
}

/// squeue's lines "id|name|state|reason" for the user's jobs that belong to @p record.
std::vector<std::vector<std::string>> queued(const FarmRecord& record) {
    std::set<std::string> ids;
    for (const auto& job : record.jobs) ids.insert(job.id);
    const std::string text = slurm("squeue", {"--me", "--noheader", "--format=%i|%j|%T|%r"});
    std::vector<std::vector<std::string>> rows;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        std::vector<std::string> fields;
        std::istringstream cells(line);
        for (std::string cell; std::getline(cells, cell, '|');) fields.push_back(cell);
        if (fields.size() < 4) continue;
        // "123_4" or "123_[5-9%2]" for array tasks.
        if (ids.count(fields[0].substr(0, fields[0].find('_')))) rows.push_back(fields);
    }
    return rows;
}

FarmSettings settingsOf(const FarmOptions& o, const Scene& scene) {
    FarmSettings s;
    s.program = fs::canonical("/proc/self/exe");
    s.scene = fs::absolute(o.scene).lexically_normal();
    s.outDir = fs::absolute(o.outDir).lexically_normal();
    s.overrides = o.overrides;
    s.frames = int(scene.simulation.frames);
    s.chunk = o.chunk;
    s.maxRunning = o.maxRunning;
    s.partition = o.partition;
    s.account = o.account;
    s.timeLimit = o.timeLimit;
    s.planAfterSurface = scene.render.mode == "surface";
    return s;
}

void submitShot(const FarmOptions& o, Reporter& reporter) {
    if (o.scene.empty()) throw SceneError("farm: name the scene file: globular farm SCENE --out DIR");
    if (o.outDir.empty()) throw SceneError("farm: --out DIR is required (a folder every node sees)");
    const Scene scene = loadScene(o.scene, o.overrides, reporter);
    FarmRecord record;
    record.settings = settingsOf(o, scene);
    record.settings.validate();
    record.meshFormat = scene.surface.meshFormat;
    record.sheet = scene.render.contactSheet > 0;
    record.movie = scene.render.movie;
    const FarmSettings& s = record.settings;
    if (o.dryRun) {
        const std::vector<std::string> placeholders = {"<sim>", "<surface>", "<plan>", "<render>",
                                                       "<finish>"};
        for (const std::string& step : kFarmSteps) {
            std::cout << "#### " << (farmDir(s.outDir) / (step + ".sbatch")).string()
                      << "  (sbatch --parsable; <step> is that step's job id)\n"
                      << farmScript(s, step, farmDependency(s, step, placeholders)) << "\n";
        }
        return;
    }
    if (fs::exists(recordPath(s.outDir))) {
        const FarmRecord old = readRecord(s.outDir);
        if (!queued(old).empty()) {
            throw Error("farm: " + s.outDir.string() + " has jobs in the queue already; see "
                        "`globular farm --status " + s.outDir.string() + "`");
        }
    }
    ensureWritableDirectory(s.outDir);
    submitSteps(record, {kFarmSteps.begin(), kFarmSteps.end()}, {}, std::cout);
}

void printStatus(const FarmOptions& o) {
    const FarmRecord r = readRecord(o.outDir);
    const FarmSettings& s = r.settings;
    const fs::path& dir = s.outDir;
    const auto chunks = farmChunks(s.frames, s.chunk);
    int caches = 0, surfaces = 0, frames = 0, surfaceChunks = 0, renderChunks = 0;
    for (int f = 1; f <= s.frames; ++f) {
        caches += fs::exists(cacheVdbPath(dir, f));
        surfaces += fs::exists(surfaceVdbPath(dir, f));
        frames += fs::exists(framePngPath(dir, f));
    }
    std::string missingSurface, missingRender;
    for (std::size_t k = 0; k < chunks.size(); ++k) {
        const auto [first, last] = chunks[k];
        if (surfaceDone(r, first, last)) ++surfaceChunks;
        else missingSurface += " " + std::to_string(k);
        if (renderDone(r, first, last)) ++renderChunks;
        else missingRender += " " + std::to_string(k);
    }
    const int total = s.frames, n = int(chunks.size());
    std::cout << "shot " << dir.string() << " (" << total << " frames, " << n << " chunks of "
              << s.chunk << ")\n"
              << "  sim      " << caches << "/" << total << " caches\n"
              << "  surface  " << surfaces << "/" << total << " frames, " << surfaceChunks << "/"
              << n << " chunks" << (missingSurface.empty() ? "" : ", missing:" + missingSurface)
              << "\n"
              << "  plan     " << (fs::exists(renderPlanPath(dir)) ? "written" : "not yet") << "\n"
              << "  render   " << frames << "/" << total << " frames, " << renderChunks << "/" << n
              << " chunks" << (missingRender.empty() ? "" : ", missing:" + missingRender) << "\n"
              << "  finish   contact sheet "
              << (!r.sheet ? "not asked" : fs::exists(dir / "contact_sheet.png") ? "written" : "not yet")
              << ", movie "
              << (!r.movie ? "not asked" : fs::exists(dir / "movie.mp4") ? "written" : "not yet")
              << "\n";
    std::map<std::string, std::string> stepOf;
    std::string ids;
    for (const auto& job : r.jobs) {
        stepOf[job.id] = job.step;
        ids += (ids.empty() ? "" : ",") + job.id;
    }
    try {
        const auto rows = queued(r);
        std::cout << "queue (squeue): " << (rows.empty() ? "no jobs of this shot\n" : "\n");
        for (const auto& row : rows) {
            std::cout << "  " << row[0] << "  " << stepOf[row[0].substr(0, row[0].find('_'))]
                      << "  " << row[2] << (row[3] == "None" ? "" : "  (" + row[3] + ")") << "\n";
        }
    } catch (const Error& e) {
        std::cout << "queue: unknown: " << e.what() << "\n";
    }
    if (ids.empty()) return;
    try {
        const std::string text = slurm("sacct", {"--noheader", "--parsable2", "--jobs=" + ids,
                                                 "--format=JobID,State,ExitCode"});
        std::cout << "accounting (sacct), tasks not COMPLETED:\n";
        std::istringstream lines(text);
        int shown = 0;
        for (std::string line; std::getline(lines, line);) {
            if (line.empty() || line.find(".batch") != std::string::npos ||
                line.find(".extern") != std::string::npos ||
                line.find("|COMPLETED|") != std::string::npos)
                continue;
            std::replace(line.begin(), line.end(), '|', ' ');
            std::cout << "  " << line << "  " << stepOf[line.substr(0, line.find_first_of("_ "))]
                      << "\n";
            ++shown;
        }
        if (shown == 0) std::cout << "  none\n";
    } catch (const Error& e) {
        std::cout << "accounting: unknown (the files above are the progress): " << e.what()
                  << "\n";
    }
}

void resubmitShot(const FarmOptions& o) {
    FarmRecord r = readRecord(o.outDir);
    const FarmSettings& s = r.settings;
    // Jobs that wait on a failed one never start: cancel them; anything else still in
    // the queue may yet finish the shot, so nothing is resubmitted beside it.
    std::vector<std::string> stuck;
    for (const auto& row : queued(r)) {
        if (row[2] == "PENDING" && row[3] == "DependencyNeverSatisfied") {
            stuck.push_back(row[0]);
        } else {
            throw Error("farm: job " + row[0] + " of " + s.outDir.string() + " is " + row[2] +
                        ": wait for the queue to drain (or scancel it), then --resubmit");
        }
    }
    if (!stuck.empty()) {
        std::vector<std::string> args = stuck;
        slurm("scancel", args);
        std::cout << "cancelled " << stuck.size() << " job(s) whose dependency failed\n";
    }
    const auto chunks = farmChunks(s.frames, s.chunk);
    std::set<std::string> steps;
    std::map<std::string, std::vector<int>> tasks;
    if (!allExist(1, s.frames, [&](int f) { return cacheVdbPath(s.outDir, f); })) {
        steps = {kFarmSteps.begin(), kFarmSteps.end()};  // sim resumes where it stopped
    } else {
        std::vector<int> surface, render;
        for (std::size_t k = 0; k < chunks.size(); ++k) {
            const auto [first, last] = chunks[k];
            const bool surfaceMissing = !surfaceDone(r, first, last);
            if (surfaceMissing) surface.push_back(int(k));
            if (surfaceMissing || !renderDone(r, first, last)) render.push_back(int(k));
        }
        if (!surface.empty()) steps.insert("surface"), tasks["surface"] = surface;
        if (!render.empty()) {
            steps.insert("plan");  // keeps a current plan; re-measures a stale one
            steps.insert("render");
            tasks["render"] = render;
        }
        if (!render.empty() || !finishDone(r)) steps.insert("finish");
    }
    if (steps.empty()) {
        std::cout << "nothing to resubmit: every frame of " << s.outDir.string()
                  << " is there, with its contact sheet and movie\n";
        return;
    }
    submitSteps(r, steps, tasks, std::cout);
}

}  // namespace

ProgramResult runProgram(const std::string& program, const std::vector<std::string>& args) {
    const fs::path path = findOnPath(program);
    if (path.empty()) {
        throw Error("farm: `" + program + "` is not on PATH: run on a machine with Slurm's "
                    "commands (a login node; Debian: apt-get install slurm-client)");
    }
    int outPipe[2], errPipe[2];
    if (pipe2(outPipe, O_CLOEXEC) != 0 || pipe2(errPipe, O_CLOEXEC) != 0) {
        throw Error("farm: cannot run " + program + ": " + std::strerror(errno));
    }
    std::vector<std::string> argv{path.string()};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<char*> raw;
    for (std::string& a : argv) raw.push_back(a.data());
    raw.push_back(nullptr);
    const pid_t pid = fork();
    if (pid < 0) throw Error("farm: cannot run " + program + ": " + std::strerror(errno));
    if (pid == 0) {
        dup2(outPipe[1], 1);
        dup2(errPipe[1], 2);
        execv(raw[0], raw.data());
        _exit(127);
    }
    close(outPipe[1]);
    close(errPipe[1]);
    ProgramResult result;
    pollfd fds[2] = {{outPipe[0], POLLIN, 0}, {errPipe[0], POLLIN, 0}};
    std::string* sinks[2] = {&result.out, &result.err};
    int open = 2;
    while (open > 0) {
        if (poll(fds, 2, -1) < 0) {
            if (errno == EINTR) continue;
            break;
        }
        for (int i = 0; i < 2; ++i) {
            if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
            char buffer[4096];
            const ssize_t n = read(fds[i].fd, buffer, sizeof buffer);
            if (n > 0) {
                sinks[i]->append(buffer, std::size_t(n));
            } else if (n == 0 || errno != EINTR) {
                close(fds[i].fd);
                fds[i].fd = -1;
                --open;
            }
        }
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (result.status == 127 && result.err.empty()) result.err = "could not be started";
    return result;
}

void runFarm(const FarmOptions& options, Reporter& reporter) {
    if (options.status + options.resubmit + !options.scene.empty() > 1 ||
        (options.dryRun && (options.status || options.resubmit))) {
        throw SceneError("farm: give either SCENE --out DIR [--dry-run], --status DIR or "
                         "--resubmit DIR");
    }
    if (options.status) return printStatus(options);
    if (options.resubmit) return resubmitShot(options);
    submitShot(options, reporter);
}

}  // namespace globular
