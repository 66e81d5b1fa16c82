#include "client/editor/editor_app.hpp"

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "client/editor/actuator_feel.hpp"
#include "client/editor/daemon_link.hpp"
#include "client/editor/documents.hpp"
#include "client/editor/editor.hpp"
#include "client/editor/evdev_buttons.hpp"
#include "client/editor/event_link.hpp"
#include "client/editor/ncurses_view.hpp"
#include "client/editor/phrase_book.hpp"
#include "common/device_error.hpp"
#include "common/monotonic_clock.hpp"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/document_error.hpp"
#include "score/registry_names.hpp"
#include "score/score_xml.hpp"

namespace vibscore::editor {

namespace {

// Now on the clock the kernel stamps key events with (EvdevDevice asks it to).
std::chrono::microseconds monotonic_now() {
    return std::chrono::microseconds(monotonic_now_us());
}

std::string stem(const std::string& path) {
    std::string name = std::filesystem::path(path).filename().string();
    for (const std::string suffix : {".score.xml", ".xml"}) {
        if (name.ends_with(suffix)) {
            return name.substr(0, name.size() - suffix.size());
        }
    }
    return name;
}

struct ButtonDevice {
    std::unique_ptr<EvdevDevice> device;
    std::unique_ptr<ButtonReader> reader;
};

// One editing session: the editor, where it saves, the daemon, the buttons and the screen.
class Session {
  public:
    explicit Session(const EditOptions& options) : options_(options) {
        try {
            daemon_ = std::make_unique<DaemonLink>();
            registry_scores_ = daemon_->list("score");
            registry_clefs_ = daemon_->list("clef");
            try {
                actuator_ = daemon_->actuator();
            } catch (const DaemonError&) {
                // A daemon that declares none, or predates the property: no feel shown.
            }
            read_registry_scores();
            events_ = std::make_unique<EventLink>();
        } catch (const DaemonError& error) {
            // Files can still be edited; playing and the registry wait for the daemon.
            daemon_.reset();
            daemon_problem_ = error.what();
        }
        load(options.target.empty() ? std::optional<std::string>() : options.target);
        if (!daemon_) {
            message_ = "no daemon: " + daemon_problem_;
        }
        const ButtonMap map = ButtonMap::parse(options.button_map);
        for (const auto& path : options.buttons) {
            ButtonDevice device;
            device.device = std::make_unique<EvdevDevice>(path, options.grab);
            device.reader = std::make_unique<ButtonReader>(*device.device, map, path);
            buttons_.push_back(std::move(device));
        }
    }

    void run() {
        Screen screen;
        while (running_) {
            const ClefEditor* clef = editor_->scheme.clef_editor();
            screen.draw(editor_->model, editor_->scheme,
                        {source_.name, message_, playing_at_,
                         clef != nullptr ? actuator_feel(clef->clef(), actuator_)
                                         : std::vector<std::string>{}});
            wait_for_input();
            while (const auto code = screen.key()) {
                // A terminal's keys carry no time: now is when the key was read.
                handle(editor_->key(*code, monotonic_now()));
            }
            read_buttons();
            serve_bus();
        }
    }

  private:
    // Opens a score: a file, a registry name, or (nullopt) a new one. Nothing changes unless
    // it succeeds, so a failed open cannot leave the session saving to the wrong place.
    void load(const std::optional<std::string>& target) {
        std::vector<ClefDeclaration> available = registry_clefs(registry_clefs_);
        std::optional<Score> score;
        const ScoreSource source =
            target ? classify_source(*target)
                   : ScoreSource{daemon_ ? ScoreSource::Kind::registry : ScoreSource::Kind::file,
                                 fresh_name()};
        if (source.kind == ScoreSource::Kind::file) {
            auto beside = clefs_beside(source.name);
            beside.insert(beside.end(), available.begin(), available.end());
            available = std::move(beside);
            if (std::filesystem::exists(source.name)) {
                score = read_score_file(source.name);
            }
        } else if (target) {
            if (!daemon_) {
                throw DaemonError(
                    "", "cannot open registry score \"" + source.name + "\": " + message_);
            }
            try {
                score = read_score(daemon_->get("score", source.name), source.name).score;
            } catch (const DaemonError& error) {
                if (!error.not_found()) {
                    throw;
                }
            }
        }
        const bool is_new = !score;
        if (is_new) {
            const std::string title =
                source.kind == ScoreSource::Kind::file ? stem(source.name) : source.name;
            score = EditorModel::blank_score(title, default_clef(available));
        }
        const std::string name = source.kind == ScoreSource::Kind::registry ? source.name : "";
        auto phrases = learned_from_others(learned_, {name, *score});
        auto editor =
            std::make_unique<Editor>(Editor{EditorModel(std::move(*score), available), {}});
        editor->model.learn_from(std::move(phrases));
        editor->scheme.set_openable(registry_scores_);
        editor->scheme.set_taken(taken_names(source));
        editor->scheme.set_clef_book(read_clef_book(editor->model, source));
        // A file opened is the user's to save over; a registry name may be a shipped score.
        const bool registry = source.kind == ScoreSource::Kind::registry;
        editor->scheme.set_destination(name_of(source), is_new || !registry, is_new && registry);
        // The feedback theme's events play registry scores: saving one offers them.
        auto events = registry ? event_scores() : std::vector<EventScore>{};
        editor->scheme.set_events(std::move(events), why_no_events(registry));
        if (editor_) {
            editor->model.carry_over(editor_->model);
        }
        editor_ = std::move(editor);
        source_ = source;
        // A new score says so in the title of a roomy screen; at 40x12 the status line's hint
        // (what Select and Back do) is what a newcomer needs before the first press.
        message_.clear();
    }

    // Every score the daemon lists (shipped, stored, composed before) teaches the proposals,
    // as a phone keyboard learns words. One that does not read teaches nothing.
    void read_registry_scores() {
        for (const auto& name : registry_scores_) {
            try {
                learned_.push_back({name, read_score(daemon_->get("score", name), name).score});
            } catch (const std::exception&) {
                continue;  // `vibscore check` is where a broken score is reported
            }
        }
    }

    // The clefs the score may use, read where they are: the registry's through the daemon
    // (Origin says which are shipped), a file score's beside it. One that does not read is left
    // out: the daemon says what is wrong with it when it plays.
    ClefBook read_clef_book(const EditorModel& model, const ScoreSource& source) const {
        std::vector<KnownClef> known;
        for (const auto& declaration : model.clef_choices()) {
            try {
                const auto beside =
                    std::filesystem::path(source.name).parent_path() / declaration.href;
                std::string text;
                bool shipped = false;
                if (source.kind == ScoreSource::Kind::file && std::filesystem::exists(beside)) {
                    text = read_document_file(beside);
                } else if (daemon_) {
                    std::string name = std::filesystem::path(declaration.href).filename().string();
                    if (name.ends_with(kClefSuffix)) {
                        name.resize(name.size() - kClefSuffix.size());
                    }
                    text = daemon_->get("clef", name);
                    shipped = daemon_->origin("clef", name) == "shipped";
                } else {
                    continue;
                }
                known.push_back({declaration, read_clef(text, declaration.href), shipped});
            } catch (const std::exception&) {
                continue;
            }
        }
        return ClefBook(std::move(known));
    }

    // The names save-as asks about before saving under them, with what each is: the registry's
    // scores (the daemon says which are shipped), or the score files beside a file.
    std::vector<TakenName> taken_names(const ScoreSource& source) const {
        std::vector<TakenName> names;
        if (source.kind == ScoreSource::Kind::registry) {
            for (const auto& name : registry_scores_) {
                names.push_back({name, registry_origin(name)});
            }
            return names;
        }
        const auto folder = std::filesystem::absolute(source.name).parent_path();
        std::error_code error;
        for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
            if (entry.path().filename().string().ends_with(".score.xml")) {
                names.push_back({stem(entry.path().string()), TakenName::What::file});
            }
        }
        return names;
    }

    // A daemon that cannot say counts the name as stored: the question then warns of the worse.
    TakenName::What registry_origin(const std::string& name) const {
        try {
            const std::string origin = daemon_ ? daemon_->origin("score", name) : "stored";
            return origin == "shipped"               ? TakenName::What::shipped
                   : origin == "stored-over-shipped" ? TakenName::What::stored_over_shipped
                                                     : TakenName::What::stored;
        } catch (const DaemonError&) {
            return TakenName::What::stored;
        }
    }

    // What save-as calls the score: its registry name, or its file name without .score.xml.
    static std::string name_of(const ScoreSource& source) {
        return source.kind == ScoreSource::Kind::registry ? source.name : stem(source.name);
    }

    // Where save-as stores a score named `name`: that registry name, or NAME.score.xml beside
    // the file being edited.
    ScoreSource renamed(const std::string& name) const {
        if (source_.kind == ScoreSource::Kind::registry) {
            return {ScoreSource::Kind::registry, name};
        }
        return {
            ScoreSource::Kind::file,
            (std::filesystem::path(source_.name).parent_path() / (name + ".score.xml")).string()};
    }

    // A registry name no score has yet: tacton-1, tacton-2, ...
    std::string fresh_name() const {
        const std::set<std::string> taken(registry_scores_.begin(), registry_scores_.end());
        for (int n = 1;; ++n) {
            const std::string name = "tacton-" + std::to_string(n);
            if (!taken.contains(name) &&
                (daemon_ || !std::filesystem::exists(name + ".score.xml"))) {
                return daemon_ ? name : name + ".score.xml";
            }
        }
    }

    ClefDeclaration default_clef(const std::vector<ClefDeclaration>& available) const {
        if (!options_.clef.empty()) {
            const auto chosen = classify_source(options_.clef);
            if (chosen.kind == ScoreSource::Kind::file) {
                const std::string href = std::filesystem::path(options_.clef).filename().string();
                return {stem(href).substr(0, stem(href).find(".clef")), href};
            }
            return {options_.clef, options_.clef + ".clef.xml"};
        }
        for (const auto& clef : available) {
            if (clef.id == "lra-phone") {
                return clef;
            }
        }
        return available.empty() ? ClefDeclaration{"lra-phone", "lra-phone.clef.xml"}
                                 : available.front();
    }

    void wait_for_input() {
        std::vector<pollfd> fds{{STDIN_FILENO, POLLIN, 0}};
        for (const auto& device : buttons_) {
            fds.push_back({device.device->fd(), POLLIN, 0});
        }
        int timeout = -1;
        if (daemon_) {
            fds.push_back({daemon_->fd(), daemon_->events(), 0});
            timeout = daemon_->timeout_ms();
        }
        const auto now = monotonic_now();
        for (const auto& device : buttons_) {
            if (const auto left = device.reader->until_long(now)) {
                const int ms = static_cast<int>(left->count() / 1000 + 1);
                timeout = timeout < 0 ? ms : std::min(timeout, ms);
            }
        }
        ::poll(fds.data(), fds.size(), timeout);
    }

    void read_buttons() {
        for (auto it = buttons_.begin(); it != buttons_.end();) {
            try {
                it->reader->set_tapping(editor_->scheme.mode() == ButtonScheme::Mode::tapping);
                for (const auto& event : it->reader->read_events()) {
                    if (event.released) {
                        editor_->release_at(event.button, event.at);
                    } else {
                        handle(editor_->press_at(event.button, event.at));
                    }
                }
                if (const auto held = it->reader->expire(monotonic_now())) {
                    handle(editor_->press_at(*held, monotonic_now()));
                }
                ++it;
            } catch (const DeviceError& error) {
                message_ = error.what();  // the keyboard still works
                it = buttons_.erase(it);
            }
        }
    }

    void serve_bus() {
        if (!daemon_) {
            return;
        }
        try {
            for (const auto& event : daemon_->process()) {
                if (!playback_ || event.id != *playback_) {
                    continue;
                }
                if (event.kind == PlaybackEvent::Kind::position) {
                    playing_at_ = Position{event.bar, event.symbol};
                } else {
                    end_playback("playback " + event.reason);
                }
            }
        } catch (const DaemonError& error) {
            message_ = error.what();
        }
    }

    void end_playback(const std::string& why) {
        playback_.reset();
        playing_at_.reset();
        editor_->scheme.set_playing(false);
        message_ = why;
    }

    void handle(const Request& request) {
        message_.clear();  // news last until the next key or button
        switch (request.kind) {
            case Request::Kind::none:
                return;
            case Request::Kind::play:
                play(request.bar);
                return;
            case Request::Kind::stop:
                stop();
                return;
            case Request::Kind::save:
                if (save()) {
                    use_for(request.event, true);
                    editor_->scheme.after_save(request.event);
                }
                return;
            case Request::Kind::save_and_quit:
                if (save()) {
                    use_for(request.event, false);
                    running_ = false;
                }
                return;
            case Request::Kind::save_as:
                if (save_as(request.name)) {
                    use_for(request.event, !request.then_quit);
                    if (request.then_quit) {
                        running_ = false;
                    } else {
                        editor_->scheme.after_save(request.event);
                    }
                }
                return;
            case Request::Kind::assign_event:
                use_for(request.event, true);
                return;
            case Request::Kind::keep_event:
                keep_event(request.event, request.name);
                return;
            case Request::Kind::hear_clef:
                hear_clef(request);
                return;
            case Request::Kind::save_clef:
                save_clef(request);
                return;
            case Request::Kind::store_clef:
                store_clef(request);
                return;
            case Request::Kind::quit:
                running_ = false;
                return;
            case Request::Kind::open:
                replace(request.name);
                return;
            case Request::Kind::new_score:
                replace(std::nullopt);
                return;
        }
    }

    // Why "use for event..." has no events to offer, with how to start the feedback service
    // (docs/feedbackd.md); "" when vibscore-feedback answers. One sentence a line: the menu
    // wraps them.
    std::string why_no_events(bool registry) {
        if (!registry) {
            return "Events play registry scores, and this is a file.\n"
                   "Save it under a name with vibscore edit NAME, then use it for an event.";
        }
        if (!daemon_) {
            return "No vibscored: " + daemon_problem_;
        }
        if (events_ && events_->live()) {
            return "";
        }
        return "The feedback service (vibscore-feedback) is not running on the session bus.\n"
               "From a checkout: ./dev daemon starts it; run vibscore edit after the "
               "export DBUS_SESSION_BUS_ADDRESS=... line it prints.\n"
               "Installed: the vibscore-feedback package; D-Bus starts it when asked.";
    }

    // What each event of the feedback theme plays now: from vibscore-feedback (asked again
    // while it does not answer, so a service started since is found), else from the theme and
    // the user's file it reads when it starts; none when neither can be read (the editor then
    // saves as it did, and "use for event..." says why).
    std::vector<EventScore> event_scores() {
        if (daemon_ && (!events_ || !events_->live())) {
            events_ = std::make_unique<EventLink>();
        }
        if (!events_) {
            return {};
        }
        try {
            return events_->events();
        } catch (const std::exception& error) {
            message_ = std::string("events: ") + error.what();
            return {};
        }
    }

    // Saved for `event`: from now on it plays the score just saved, for this user. `ask`: offer
    // "keep as it was" (not when quitting).
    void use_for(const std::string& event, bool ask) {
        if (event.empty() || !events_) {
            return;
        }
        try {
            events_->assign(event, source_.name);
            // Without the service the choice is in the user's file, which it reads when it
            // starts: true, but not yet heard.
            message_ = event + " plays " + source_.name +
                       (events_->live() ? "" : " once vibscore-feedback runs");
            if (ask) {
                editor_->scheme.show_assigned(event, source_.name);
            }
            auto events = event_scores();
            editor_->scheme.set_events(std::move(events), why_no_events(true));
        } catch (const std::exception& error) {
            message_ = "saved; not used for " + event_label(event) + ": " + error.what();
        }
    }

    void keep_event(const std::string& event, const std::string& score) {
        try {
            events_->assign(event, score);
            message_ = event_label(event) + " plays " +
                       (score.empty() ? std::string("the theme's score") : score) + " again";
            auto events = event_scores();
            editor_->scheme.set_events(std::move(events), why_no_events(true));
        } catch (const std::exception& error) {
            message_ = event_label(event) + ": " + error.what();
        }
    }

    // The string at the number under the cursor, through the clef as it is being edited: a
    // quarter note, sent with the clef inline, on the actuator at once.
    void hear_clef(const Request& request) {
        if (!daemon_) {
            message_ = "cannot hear it: no daemon";
            return;
        }
        const std::string href = "edited.clef.xml";
        const std::string score = "<VibScore><Title>" + request.name +
                                  "</Title><Clef id=\"edited\" href=\"" + href +
                                  "\"/><Bar clef=\"edited\"><Note length=\"quarter\" number=\"" +
                                  std::to_string(request.number) + "\" string=\"" +
                                  std::to_string(request.string) + "\"/></Bar></VibScore>";
        try {
            daemon_->audition(score, {{href, request.document}});
        } catch (const DaemonError& error) {
            message_ = "cannot hear it: " + std::string(error.what());
        }
    }

    // Stores the edited clef under a new name (the registry, or a file beside a file score) and
    // the bars at the cursor use it.
    // Writes the clef where the score will find it: beside a file score, or in the registry.
    // False (and says why) where there is neither.
    bool store_clef_document(const Request& request, const char* not_done) {
        const std::string href = request.name + std::string(kClefSuffix);
        if (source_.kind == ScoreSource::Kind::file) {
            const auto path = std::filesystem::path(source_.name).parent_path() / href;
            write_document_file(path, request.document);
        } else if (daemon_) {
            daemon_->compose(request.name, request.document);
        } else {
            message_ = std::string(not_done) + ": no daemon";
            return false;
        }
        return true;
    }

    // A tempo clef the tapped bars already use: stored, or the status line says it is not.
    void store_clef(const Request& request) {
        try {
            read_clef(request.document, request.name + std::string(kClefSuffix));
            store_clef_document(request, ("clef " + request.name + " not stored").c_str());
        } catch (const std::exception& error) {
            message_ = "clef " + request.name + " not stored: " + std::string(error.what());
        }
    }

    void save_clef(const Request& request) {
        const std::string href = request.name + std::string(kClefSuffix);
        try {
            const Clef clef = read_clef(request.document, href);
            if (!store_clef_document(request, "clef not saved")) {
                return;
            }
            const ClefDeclaration declaration{request.name, href};
            editor_->scheme.add_clef({declaration, clef, false});
            editor_->model.add_available_clef(declaration);
            editor_->model.set_bar_clef(request.name);
            message_ = "clef " + request.name + " saved; bar " +
                       std::to_string(editor_->model.cursor().bar + 1) + " uses it";
        } catch (const std::exception& error) {
            message_ = "clef not saved: " + std::string(error.what());
        }
    }

    void play(std::size_t bar) {
        if (!daemon_) {
            message_ = "cannot play: no daemon";
            return;
        }
        try {
            playback_ = daemon_->play(registry_document(editor_->model.score()), bar);
            editor_->scheme.set_playing(true);
            playing_at_ = Position{bar, 0};  // the status line names the bar playing now
        } catch (const DaemonError& error) {
            message_ = "cannot play: " + std::string(error.what());
        }
    }

    void stop() {
        if (playback_ && daemon_) {
            try {
                daemon_->stop(*playback_);
            } catch (const DaemonError& error) {
                message_ = error.what();
            }
        }
        end_playback("stopped");
    }

    bool save() {
        auto& model = editor_->model;
        try {
            if (model.score().title.empty()) {
                model.set_title(source_.kind == ScoreSource::Kind::file ? stem(source_.name)
                                                                        : source_.name);
            }
            if (source_.kind == ScoreSource::Kind::file) {
                write_score_file(source_.name, model.score());
                message_ = "saved " + source_.name;
            } else {
                if (!daemon_) {
                    message_ = "cannot save: no daemon";
                    return false;
                }
                daemon_->compose(source_.name, registry_document(model.score()));
                message_ = "saved as " + source_.name;
                if (std::find(registry_scores_.begin(), registry_scores_.end(), source_.name) ==
                    registry_scores_.end()) {
                    registry_scores_.push_back(source_.name);
                    std::sort(registry_scores_.begin(), registry_scores_.end());
                    editor_->scheme.set_openable(registry_scores_);
                }
            }
            model.mark_saved();
            editor_->scheme.set_destination(name_of(source_), true);
            return true;
        } catch (const std::exception& error) {
            message_ = "not saved: " + std::string(error.what());
            return false;
        }
    }

    // Saves under another name, which the editor then edits: the score opened stays as it was
    // (a shipped one is never changed; a stored score of that name shadows it).
    bool save_as(const std::string& name) {
        const ScoreSource before = source_;
        auto& model = editor_->model;
        const std::string old_title = model.score().title;
        if (old_title.empty() || old_title == name_of(before)) {
            model.set_title(name);  // a score titled by its name keeps being so
        }
        source_ = renamed(name);
        if (!save()) {
            source_ = before;
            if (model.score().title != old_title) {
                model.set_title(old_title);
            }
            return false;
        }
        editor_->scheme.set_taken(taken_names(source_));
        return true;
    }

    // Opens another score or a new one; unsaved changes need the request twice.
    void replace(const std::optional<std::string>& target) {
        const std::string wanted = target ? *target : "<new>";
        if (editor_->model.modified() && pending_replace_ != wanted) {
            pending_replace_ = wanted;
            message_ = "unsaved changes: do it again to discard them";
            return;
        }
        pending_replace_.clear();
        try {
            load(target);
        } catch (const std::exception& error) {
            message_ = error.what();
        }
    }

    EditOptions options_;
    std::unique_ptr<DaemonLink> daemon_;
    std::map<std::string, std::string> actuator_;  // Haptics1.Actuator, for the clef window
    std::unique_ptr<EventLink> events_;            // the feedback theme's events ("use for ...")
    std::vector<std::string> registry_scores_;
    std::vector<std::string> registry_clefs_;
    std::vector<NamedScore> learned_;  // the registry's scores the proposals learn from
    std::unique_ptr<Editor> editor_;
    ScoreSource source_;
    std::vector<ButtonDevice> buttons_;
    std::optional<std::uint64_t> playback_;
    std::optional<Position> playing_at_;
    std::string message_;
    std::string daemon_problem_;  // why there is no daemon, when there is none
    std::string pending_replace_;
    bool running_ = true;
};

}  // namespace

int run_editor(const EditOptions& options, std::ostream& err) {
    if (!isatty(STDIN_FILENO) || !isatty(STDOUT_FILENO)) {
        err << "vibscore edit: needs a terminal\n";
        return 1;
    }
    try {
        Session session(options);
        session.run();
        return 0;
    } catch (const DocumentError& error) {
        err << error.what() << "\n";
    } catch (const DeviceError& error) {
        err << "vibscore edit: " << error.what() << "\n";
    } catch (const std::invalid_argument& error) {
        err << "vibscore edit: " << error.what() << "\n";
        return 2;
    } catch (const std::exception& error) {
        err << "vibscore edit: " << error.what() << "\n";
    }
    return 1;
}

}  // namespace vibscore::editor
