# bash completion for vibscore. The verbs and their options come from the client's own table
# (vibscore --completion-words), so they are those of its --help; registry names come from the
# running daemon (vibscore list); when it is not running, only files are offered. What follows
# an option or a verb (file patterns, formats, registry names) is said here.

# One line per command: its words, then its options, a valued one ending in '='.
_vibscore_table() {
    "$1" --completion-words 2>/dev/null
}

_vibscore_registry() {
    "$1" list "$2" 2>/dev/null | cut -f1
}

# Files whose names match a pattern, and folders to walk into (ending in '/', no space after).
_vibscore_files() {
    local cur=$1 pattern=$2 entry
    local IFS=$'\n'
    for entry in $(compgen -d -- "$cur"); do
        COMPREPLY+=("$entry/")
    done
    for entry in $(compgen -f -- "$cur"); do
        [[ -d $entry ]] && continue
        [[ $entry == $pattern ]] && COMPREPLY+=("$entry")
    done
    compopt -o nospace -o filenames 2>/dev/null
    # A lone file name completes to a whole word: let bash add the space after it.
    if [[ ${#COMPREPLY[@]} -eq 1 && ${COMPREPLY[0]} != */ ]]; then
        compopt +o nospace 2>/dev/null
    fi
}

_vibscore() {
    local cur prev verb i program
    COMPREPLY=()
    cur=${COMP_WORDS[COMP_CWORD]}
    prev=${COMP_WORDS[COMP_CWORD-1]}
    program=${COMP_WORDS[0]}
    local table verbs= valued= options= subverbs= word sub= mine own j
    local -a fields arguments=()
    table=$(_vibscore_table "$program")
    # What convert reads (--from) and writes (--to).
    local readable="score ahap android-json android-xml rtttl midi"
    local writable="score ahap android-json android-xml android-envelope midi"

    verb=
    for ((i = 1; i < COMP_CWORD; i++)); do
        case ${COMP_WORDS[i]} in
            -*) ;;
            *) verb=${COMP_WORDS[i]}; break ;;
        esac
    done

    # The word after the verb, which names a sub-verb (clef fit) when the verb has them.
    for ((j = i + 1; j < COMP_CWORD; j++)); do
        [[ ${COMP_WORDS[j]} != -* ]] && sub=${COMP_WORDS[j]} && break
    done

    # The verbs; of the one typed, its options, its sub-verbs (clef: fit) and what each of its
    # arguments completes to (after ':', one by one; of a sub-verb's line, counted after it);
    # every valued option.
    while read -ra fields; do
        [[ ${#fields[@]} -eq 0 ]] && continue
        [[ " $verbs " == *" ${fields[0]} "* ]] || verbs+=" ${fields[0]}"
        mine= own=
        [[ ${fields[0]} == "$verb" ]] && mine=1 own=1
        for word in "${fields[@]:1}"; do
            case $word in
                -*)
                    [[ $word == *= ]] && valued+="|${word%=}"
                    [[ -n $mine ]] && options+=" ${word%=}" ;;
                :*)
                    [[ -n $own ]] && arguments+=("${word#:}") ;;
                *)
                    if [[ -n $mine ]]; then
                        subverbs+=" $word"
                        if [[ $word == "$sub" ]]; then
                            arguments=("")
                        else
                            own=
                        fi
                    fi ;;
            esac
        done
    done <<< "$table"
    valued=${valued#|}

    if [[ -z $verb ]]; then
        COMPREPLY=($(compgen -W "$verbs --help --version" -- "$cur"))
        return
    fi

    case $prev in
        --usage)
            COMPREPLY=($(compgen -W "ringtone alarm notification communication accessibility hardware-feedback touch media" -- "$cur"))
            return ;;
        --clef)
            COMPREPLY=($(compgen -W "$(_vibscore_registry "$program" clefs)" -- "$cur"))
            # convert reads the clef itself: a clef file too.
            [[ $verb == convert ]] && _vibscore_files "$cur" '*.xml'
            return ;;
        --from)
            COMPREPLY=($(compgen -W "$readable" -- "$cur"))
            return ;;
        --to)
            COMPREPLY=($(compgen -W "$writable" -- "$cur"))
            return ;;
        --svg|--png)
            _vibscore_files "$cur" "*.${prev#--}"
            return ;;
        --clefs)
            _vibscore_files "$cur" '*/'
            return ;;
        --actuator)
            # clef fit takes the word daemon for vibscored's own declaration.
            [[ $verb == clef ]] && COMPREPLY=($(compgen -W "daemon" -- "$cur"))
            _vibscore_files "$cur" '*.conf'
            return ;;
        -o|--output)
            # calibrate --plan writes a drive trace; clef fit a clef.
            if [[ $verb == calibrate ]]; then
                _vibscore_files "$cur" '*.csv'
            else
                _vibscore_files "$cur" '*.xml'
            fi
            return ;;
        --kind)
            COMPREPLY=($(compgen -W "erm lra" -- "$cur"))
            return ;;
        --estimate)
            _vibscore_files "$cur" '*.csv'
            return ;;
        --out)
            _vibscore_files "$cur" '*.@(csv|wav)'
            return ;;
        --buttons)
            _vibscore_files "${cur:-/dev/input/}" '*'
            return ;;
        *)
            # Any other valued option takes a value of its own (a number, a key map).
            [[ -n $valued && $prev == @($valued) ]] && return ;;
    esac

    if [[ $cur == -* ]]; then
        COMPREPLY=($(compgen -W "$options" -- "$cur"))
        return
    fi

    # How many positional words the verb already has.
    local position=0
    for ((i = i + 1; i < COMP_CWORD; i++)); do
        if [[ -n $valued && ${COMP_WORDS[i]} == @($valued) ]]; then
            ((i++))
        elif [[ ${COMP_WORDS[i]} != -* ]]; then
            ((position++))
        fi
    done

    # A verb made of sub-verbs (clef) first takes one of them.
    if [[ -n $subverbs && $position -eq 0 ]]; then
        COMPREPLY=($(compgen -W "$subverbs" -- "$cur"))
        return
    fi

    # The table's sources for this argument ("..." on the last: every later one too).
    local spec= source fixed= kind
    local -a sources
    if ((position < ${#arguments[@]})); then
        spec=${arguments[position]}
    elif ((${#arguments[@]} > 0)) && [[ ${arguments[-1]} == *... ]]; then
        spec=${arguments[-1]}
    fi
    IFS=, read -ra sources <<< "${spec%...}"
    for source in "${sources[@]}"; do
        case $source in
            @scores|@clefs)
                COMPREPLY+=($(compgen -W "$(_vibscore_registry "$program" "${source#@}")" -- "$cur")) ;;
            @kind)
                # The registry's names of the kind the word before names (get clef NAME).
                kind=${COMP_WORDS[COMP_CWORD-1]}
                COMPREPLY+=($(compgen -W "$(_vibscore_registry "$program" "${kind%s}s")" -- "$cur")) ;;
            @events)
                COMPREPLY+=($(compgen -W "$("$program" assign --list 2>/dev/null | cut -d' ' -f1)" -- "$cur")) ;;
            @drivers)
                COMPREPLY+=($(compgen -W "$("$program" drivers 2>/dev/null | cut -c3- | cut -f1)" -- "$cur")) ;;
            *'*'*)
                _vibscore_files "$cur" "$source" ;;
            *)
                fixed+=" $source" ;;
        esac
    done
    [[ -n $fixed ]] && COMPREPLY+=($(compgen -W "$fixed" -- "$cur"))
}

# The patterns above (@(csv|wav)) are extended globs; bash-completion enables extglob, a bare
# bash does not.
shopt -s extglob
complete -F _vibscore vibscore build/client/vibscore ./build/client/vibscore
