# bash completion for vibscore. Registry names come from the running daemon (vibscore list);
# when it is not running, only files are offered.

_vibscore_registry() {
    vibscore list "$1" 2>/dev/null | cut -f1
}

_vibscore() {
    local cur prev verb i
    COMPREPLY=()
    cur=${COMP_WORDS[COMP_CWORD]}
    prev=${COMP_WORDS[COMP_CWORD-1]}
    local verbs="check render info play stop list get compose delete show edit drivers driver convert"
    local formats="score ahap android-json android-xml android-envelope rtttl midi"

    verb=
    for ((i = 1; i < COMP_CWORD; i++)); do
        case ${COMP_WORDS[i]} in
            -*) ;;
            *) verb=${COMP_WORDS[i]}; break ;;
        esac
    done

    if [[ -z $verb ]]; then
        COMPREPLY=($(compgen -W "$verbs --help --version" -- "$cur"))
        return
    fi

    case $prev in
        --usage)
            COMPREPLY=($(compgen -W "ringtone alarm notification communication accessibility hardware-feedback touch media" -- "$cur"))
            return ;;
        --clef)
            COMPREPLY=($(compgen -W "$(_vibscore_registry clefs)" -- "$cur"))
            # convert reads the clef itself: a clef file too.
            [[ $verb == convert ]] &&
                COMPREPLY+=($(compgen -f -X '!*.xml' -- "$cur") $(compgen -d -- "$cur"))
            return ;;
        --from|--to)
            COMPREPLY=($(compgen -W "$formats" -- "$cur"))
            return ;;
        --svg|--png)
            COMPREPLY=($(compgen -f -X "!*.${prev#--}" -- "$cur") $(compgen -d -- "$cur"))
            return ;;
        --track)
            return ;;
        --out)
            COMPREPLY=($(compgen -f -X '!*.@(csv|wav)' -- "$cur") $(compgen -d -- "$cur"))
            return ;;
        --rate|--repeat|--intensity|--width|--buttons|--keymap)
            [[ $prev == --buttons ]] && COMPREPLY=($(compgen -f -- "${cur:-/dev/input/}"))
            return ;;
    esac

    if [[ $cur == -* ]]; then
        local options="--help"
        case $verb in
            render) options+=" --rate --out --plot --width --svg --png" ;;
            play) options+=" --usage --repeat --clef --intensity --wait" ;;
            show) options+=" --width --colour --svg --png" ;;
            convert) options+=" --from --to --clef --track --loop" ;;
            edit) options+=" --buttons --keymap --grab --clef" ;;
        esac
        COMPREPLY=($(compgen -W "$options" -- "$cur"))
        return
    fi

    # How many positional words the verb already has.
    local position=0
    for ((i = i + 1; i < COMP_CWORD; i++)); do
        case ${COMP_WORDS[i]} in
            --usage|--clef|--out|--rate|--repeat|--intensity|--width|--buttons|--keymap) ((i++)) ;;
            --from|--to|--track|--svg|--png) ((i++)) ;;
            -*) ;;
            *) ((position++)) ;;
        esac
    done

    case $verb in
        check|render|info)
            COMPREPLY=($(compgen -f -X '!*.xml' -- "$cur") $(compgen -d -- "$cur")) ;;
        play|show|edit)
            [[ $position -eq 0 ]] &&
                COMPREPLY=($(compgen -W "$(_vibscore_registry scores)" -- "$cur")
                           $(compgen -f -X '!*.xml' -- "$cur") $(compgen -d -- "$cur")) ;;
        list)
            [[ $position -eq 0 ]] && COMPREPLY=($(compgen -W "scores clefs" -- "$cur")) ;;
        get|delete)
            if [[ $position -eq 0 ]]; then
                COMPREPLY=($(compgen -W "score clef" -- "$cur"))
            elif [[ $position -eq 1 ]]; then
                local kind=${COMP_WORDS[COMP_CWORD-1]}
                COMPREPLY=($(compgen -W "$(_vibscore_registry "${kind}s")" -- "$cur"))
            fi ;;
        compose)
            [[ $position -eq 1 ]] &&
                COMPREPLY=($(compgen -f -X '!*.xml' -- "$cur") $(compgen -d -- "$cur")) ;;
        convert)
            if [[ $position -eq 0 ]]; then
                COMPREPLY=($(compgen -f -X '!*.@(xml|ahap|json|rtttl|rtx|mid|midi)' -- "$cur")
                           $(compgen -d -- "$cur"))
            elif [[ $position -eq 1 ]]; then
                COMPREPLY=($(compgen -f -- "$cur"))
            fi ;;
        driver)
            [[ $position -eq 0 ]] &&
                COMPREPLY=($(compgen -W "$(vibscore drivers 2>/dev/null | cut -c3- | cut -f1)" -- "$cur")) ;;
    esac
}

complete -F _vibscore vibscore
